//! `cargo run --release --example labs`: lists every lab of `labs::ALL` — its example name,
//! lecture, original title, default size, keys and parameters — as Markdown (`--markdown`) or
//! plain text. Needs no GPU.

use shaderlab::labs;

fn main() {
    let markdown = std::env::args().any(|a| a == "--markdown");
    if markdown {
        println!("| example | lecture | effect | size | keys and mouse | parameters (`--set`) |");
        println!("|---|---|---|---|---|---|");
    }
    for entry in labs::ALL {
        let info = entry.info;
        let params = (entry.params)();
        let names: Vec<String> = params
            .specs()
            .iter()
            .map(|s| format!("`{}`={}", s.name, s.default_text()))
            .collect();
        let keys = info.keys.help();
        let keys = keys.split_whitespace().collect::<Vec<_>>().join(" ");
        if markdown {
            println!(
                "| `{}` | {} | {} {} | {}x{} | {} | {} |",
                info.name,
                info.lecture,
                info.title,
                info.label,
                info.size.0,
                info.size.1,
                keys.replace('|', "\\|"),
                names.join(" ")
            );
        } else {
            println!(
                "{} ({}, {} {}, {}x{})",
                info.name, info.lecture, info.title, info.label, info.size.0, info.size.1
            );
            println!("  keys: {keys}");
            println!("  parameters: {}\n", names.join(" "));
        }
    }
}
