//! `cargo run --release --example labs`: lists every lab of `course::ALL` — its example name,
//! lecture, original title, default size, keys and parameters — as Markdown (`--markdown`) or
//! plain text. Needs no GPU.

use std::fmt::Write as _;

use shaderlab::course;

fn main() -> std::process::ExitCode {
    let markdown = std::env::args().any(|a| a == "--markdown");
    let mut out = String::new();
    if markdown {
        out.push_str("| example | lecture | effect | size | keys and mouse | parameters (`--set`) |\n");
        out.push_str("|---|---|---|---|---|---|\n");
    }
    for entry in course::ALL {
        let info = entry.info;
        let params = (entry.params)();
        let names: Vec<String> = params
            .specs()
            .iter()
            .map(|s| format!("`{}`={}", s.name, s.default_text()))
            .collect();
        let keys = info.keys.help();
        let keys = keys.split_whitespace().collect::<Vec<_>>().join(" ");
        // Writing into a String cannot fail.
        let _ = if markdown {
            writeln!(
                out,
                "| `{}` | {} | {} {} | {}x{} | {} | {} |",
                info.name,
                info.lecture,
                info.original_title,
                info.label,
                info.size.0,
                info.size.1,
                keys.replace('|', "\\|"),
                names.join(" ")
            )
        } else {
            writeln!(
                out,
                "{} ({}, {} {}, {}x{})\n  keys: {keys}\n  parameters: {}\n",
                info.name,
                info.lecture,
                info.original_title,
                info.label,
                info.size.0,
                info.size.1,
                names.join(" ")
            )
        };
    }
    shaderlab::shell::tool_exit("labs", shaderlab::shell::print(&out).map_err(anyhow::Error::from))
}
