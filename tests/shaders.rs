#[test]
fn t() {
    let out = std::process::Command::new(env!("CARGO")).args(["build", "--release", "--example", "phong", "--message-format=short"]).current_dir(env!("CARGO_MANIFEST_DIR")).output().unwrap();
    println!("{:?} {}", out.status, String::from_utf8_lossy(&out.stderr));
}
