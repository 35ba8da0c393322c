//! The site `scripts/web` builds, as a host serves it: every file has a gzip and a brotli copy
//! beside it holding the same bytes, the module as browsers download it stays small, and
//! `scripts/web-serve.py` (behind `scripts/web --serve`) sends the copy the request's
//! `Accept-Encoding` takes, with `Content-Encoding`, the original's `Content-Type` and
//! `Vary: Accept-Encoding`.
//!
//! They need the site, python3, gzip and brotli, which the native build does not: they are
//! `#[ignore]`d in `cargo test` and run by `.ci/web` after `scripts/web`.

mod common;

use std::io::{Read, Write};
use std::net::{TcpListener, TcpStream};
use std::path::Path;
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

use common::site;

/// The module as browsers download it (gzip, which every browser takes) at most: over a
/// 20 Mbit/s link it arrives in under a second.
const MAX_WASM_GZ: u64 = 2_300_000;

/// `tool -dc file`'s output; a missing tool is a failure naming its package.
fn decompress(tool: &str, file: &Path) -> Vec<u8> {
    let out = Command::new(tool)
        .arg("-dc")
        .arg(file)
        .output()
        .unwrap_or_else(|e| panic!("{tool}: {e} (sudo apt-get install -y {tool})"));
    assert!(
        out.status.success(),
        "{tool} -dc {}: {}",
        file.display(),
        String::from_utf8_lossy(&out.stderr)
    );
    out.stdout
}

#[test]
#[ignore = "needs the site (scripts/web), gzip and brotli: run by .ci/web"]
fn every_file_of_the_site_has_gzip_and_brotli_copies_of_the_same_bytes() {
    let dir = site();
    for name in ["index.html", "web.js", "web_bg.wasm"] {
        let original = std::fs::read(dir.join(name)).unwrap();
        for (tool, suffix) in [("gzip", "gz"), ("brotli", "br")] {
            let copy = dir.join(format!("{name}.{suffix}"));
            assert!(copy.is_file(), "no {} beside {name}", copy.display());
            assert!(
                decompress(tool, &copy) == original,
                "{} does not hold {name}'s bytes",
                copy.display()
            );
            let (raw, packed) = (original.len(), std::fs::metadata(&copy).unwrap().len());
            assert!(
                packed < raw as u64,
                "{} ({packed} bytes) is not smaller than {name} ({raw})",
                copy.display()
            );
        }
    }
    let gz = std::fs::metadata(dir.join("web_bg.wasm.gz")).unwrap().len();
    assert!(
        gz <= MAX_WASM_GZ,
        "web_bg.wasm.gz is {gz} bytes, more than {MAX_WASM_GZ}: the page's first frame waits for it"
    );
}

/// `scripts/web-serve.py DIR PORT`, stopped when dropped.
struct Server {
    child: Child,
    port: u16,
}

impl Drop for Server {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

/// `scripts/web-serve.py DIR PORT` with its stderr in `log`.
fn serve(dir: &Path, log: &Path) -> Server {
    let port = TcpListener::bind("127.0.0.1:0").unwrap().local_addr().unwrap().port();
    let script = Path::new(env!("CARGO_MANIFEST_DIR")).join("scripts/web-serve.py");
    let child = Command::new("python3")
        .arg(&script)
        .arg(dir)
        .arg(port.to_string())
        .stdout(Stdio::null())
        .stderr(std::fs::File::create(log).unwrap())
        .spawn()
        .unwrap_or_else(|e| panic!("python3 {}: {e} (sudo apt-get install -y python3)", script.display()));
    let mut server = Server { child, port };
    let start = Instant::now();
    while TcpStream::connect(("127.0.0.1", port)).is_err() {
        if let Ok(Some(status)) = server.child.try_wait() {
            panic!("{} exited ({status}) before serving", script.display());
        }
        assert!(
            start.elapsed() < Duration::from_secs(120),
            "nothing listens on port {port}"
        );
        std::thread::sleep(Duration::from_millis(50));
    }
    server
}

/// One GET: the status line, the headers (names lower-cased) and the body.
fn get(port: u16, path: &str, accept_encoding: Option<&str>) -> (String, Vec<(String, String)>, Vec<u8>) {
    let mut stream = TcpStream::connect(("127.0.0.1", port)).unwrap();
    stream.set_read_timeout(Some(Duration::from_secs(120))).unwrap();
    let mut request = format!("GET {path} HTTP/1.0\r\nHost: 127.0.0.1\r\n");
    if let Some(ae) = accept_encoding {
        request += &format!("Accept-Encoding: {ae}\r\n");
    }
    request += "\r\n";
    stream.write_all(request.as_bytes()).unwrap();
    let mut response = Vec::new();
    stream.read_to_end(&mut response).unwrap();
    let split = response
        .windows(4)
        .position(|w| w == b"\r\n\r\n")
        .expect("a response head");
    let head = String::from_utf8_lossy(&response[..split]).into_owned();
    let mut lines = head.lines();
    let status = lines.next().unwrap_or("").to_string();
    let headers = lines
        .filter_map(|l| l.split_once(':'))
        .map(|(k, v)| (k.trim().to_ascii_lowercase(), v.trim().to_string()))
        .collect();
    (status, headers, response[split + 4..].to_vec())
}

fn header<'a>(headers: &'a [(String, String)], name: &str) -> Option<&'a str> {
    headers.iter().find(|(k, _)| k == name).map(|(_, v)| v.as_str())
}

/// A request and what must come back: path, `Accept-Encoding`, body, `Content-Encoding`,
/// `Content-Type`.
type Case = (
    &'static str,
    Option<&'static str>,
    &'static str,
    Option<&'static str>,
    &'static str,
);

#[test]
#[ignore = "needs python3: run by .ci/web"]
fn the_server_sends_the_copy_the_request_accepts_with_its_encoding_and_the_originals_type() {
    let dir = std::env::temp_dir().join(format!("shaderlab-web-serve-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    // Each copy's bytes say which file went out (the server compresses nothing itself).
    for (name, body) in [
        ("index.html", "<p>page</p>"),
        ("web_bg.wasm", "module"),
        ("web.js", "script"),
    ] {
        std::fs::write(dir.join(name), body).unwrap();
        std::fs::write(dir.join(format!("{name}.gz")), format!("gz of {body}")).unwrap();
        std::fs::write(dir.join(format!("{name}.br")), format!("br of {body}")).unwrap();
    }
    std::fs::write(dir.join("plain.js"), "no copies").unwrap();
    let log = std::env::temp_dir().join(format!("shaderlab-web-serve-{}.log", std::process::id()));
    let server = serve(&dir, &log);

    let cases: &[Case] = &[
        (
            "/web_bg.wasm",
            Some("gzip, deflate, br"),
            "br of module",
            Some("br"),
            "application/wasm",
        ),
        (
            "/web_bg.wasm",
            Some("gzip, deflate"),
            "gz of module",
            Some("gzip"),
            "application/wasm",
        ),
        ("/web_bg.wasm", None, "module", None, "application/wasm"),
        (
            "/web_bg.wasm",
            Some("br;q=0, gzip"),
            "gz of module",
            Some("gzip"),
            "application/wasm",
        ),
        ("/web_bg.wasm", Some("identity"), "module", None, "application/wasm"),
        ("/web.js", Some("br"), "br of script", Some("br"), "text/javascript"),
        ("/", Some("gzip"), "gz of <p>page</p>", Some("gzip"), "text/html"),
        (
            "/index.html?lab=phong",
            Some("br, gzip"),
            "br of <p>page</p>",
            Some("br"),
            "text/html",
        ),
        ("/plain.js", Some("br, gzip"), "no copies", None, "text/javascript"),
    ];
    for &(path, ae, body, encoding, kind) in cases {
        let (status, headers, got) = get(server.port, path, ae);
        let what = format!("GET {path} with Accept-Encoding {ae:?}");
        assert!(status.contains(" 200 "), "{what}: {status}");
        assert_eq!(String::from_utf8_lossy(&got), body, "{what}: the wrong file");
        assert_eq!(header(&headers, "content-encoding"), encoding, "{what}");
        let got_kind = header(&headers, "content-type").unwrap_or("");
        assert!(
            got_kind.starts_with(kind),
            "{what}: Content-Type {got_kind}, not {kind}"
        );
        assert_eq!(
            header(&headers, "content-length"),
            Some(body.len().to_string().as_str()),
            "{what}"
        );
        if path != "/plain.js" {
            assert_eq!(header(&headers, "vary"), Some("Accept-Encoding"), "{what}");
        }
    }

    // A copy older than its original (a site half rebuilt) is not sent: the original is.
    std::thread::sleep(Duration::from_millis(1100));
    std::fs::write(dir.join("web.js"), "newer script").unwrap();
    let (_, headers, got) = get(server.port, "/web.js", Some("gzip, br"));
    assert_eq!(String::from_utf8_lossy(&got), "newer script");
    assert_eq!(header(&headers, "content-encoding"), None);

    let (status, _, _) = get(server.port, "/missing.wasm", Some("gzip, br"));
    assert!(status.contains(" 404 "), "a missing file: {status}");
    drop(server);
    let _ = std::fs::remove_dir_all(&dir);
    let _ = std::fs::remove_file(&log);
}

#[test]
#[ignore = "needs python3 and mkfifo: run by .ci/web"]
fn the_server_sends_only_regular_files_inside_its_folder_and_answers_a_malformed_path_with_400() {
    let top = std::env::temp_dir().join(format!("shaderlab-web-serve-inside-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&top);
    let (dir, outside) = (top.join("site"), top.join("outside"));
    std::fs::create_dir_all(dir.join("sub")).unwrap();
    std::fs::create_dir_all(&outside).unwrap();
    std::fs::write(dir.join("index.html"), "<p>page</p>").unwrap();
    std::fs::write(dir.join("web.js"), "script").unwrap();
    std::fs::write(dir.join("sub/a.txt"), "in a folder").unwrap();
    std::fs::write(outside.join("secret.txt"), "SECRET").unwrap();
    // Links planted inside the folder: to a file outside it, to a folder outside it, as the
    // precompressed copy of a file, and one to a file inside (served: its real path is inside).
    std::os::unix::fs::symlink(outside.join("secret.txt"), dir.join("leak.txt")).unwrap();
    std::os::unix::fs::symlink(&outside, dir.join("out")).unwrap();
    std::os::unix::fs::symlink(outside.join("secret.txt"), dir.join("web.js.gz")).unwrap();
    std::os::unix::fs::symlink("index.html", dir.join("alias.html")).unwrap();
    // A pipe is not a regular file (opening it to read would wait for a writer forever).
    let mkfifo = Command::new("mkfifo").arg(dir.join("pipe")).status().expect("mkfifo");
    assert!(mkfifo.success(), "mkfifo {}", dir.join("pipe").display());
    let log = top.join("server.log");
    let server = serve(&dir, &log);

    let cases: &[(&str, &str, Option<&str>)] = &[
        ("/", "200", Some("<p>page</p>")),
        ("/alias.html", "200", Some("<p>page</p>")),
        ("/sub/a.txt", "200", Some("in a folder")),
        ("/%00", "400", None),
        ("/index.html%00.js", "400", None),
        ("/index.html%0a", "400", None),
        ("/%ff.html", "400", None),
        ("/../outside/secret.txt", "400", None),
        ("/%2e%2e/outside/secret.txt", "400", None),
        ("/%2E%2E%2Foutside%2Fsecret.txt", "400", None),
        ("/sub/..%2f..%2foutside/secret.txt", "400", None),
        ("/sub/%2e%2e/index.html", "400", None),
        ("/./index.html", "400", None),
        ("http://127.0.0.1/index.html", "400", None),
        ("/leak.txt", "404", None),
        ("/out/secret.txt", "404", None),
        ("/sub/", "404", None),
        ("/sub", "404", None),
        ("/pipe", "404", None),
        ("/index.html/", "404", None),
    ];
    for &(path, code, body) in cases {
        let (status, _, got) = get(server.port, path, None);
        let got = String::from_utf8_lossy(&got);
        assert!(
            status.contains(&format!(" {code} ")),
            "GET {path}: {status}, not {code}\n{got}"
        );
        match body {
            Some(body) => assert_eq!(got, body, "GET {path}: the wrong file"),
            None => {
                assert!(!got.is_empty(), "GET {path}: {status} without a body");
                assert!(
                    !got.contains("SECRET"),
                    "GET {path}: a file outside the folder went out"
                );
                assert!(!got.contains("a.txt"), "GET {path}: a folder was listed\n{got}");
            }
        }
    }
    // The copy is a link out of the folder: the original goes out instead.
    let (status, headers, got) = get(server.port, "/web.js", Some("gzip"));
    assert!(status.contains(" 200 "), "GET /web.js: {status}");
    assert_eq!(
        String::from_utf8_lossy(&got),
        "script",
        "GET /web.js: the linked copy went out"
    );
    assert_eq!(header(&headers, "content-encoding"), None);

    drop(server);
    let log_text = std::fs::read_to_string(&log).unwrap();
    assert!(
        log_text.contains(r#""GET /%00 HTTP/1.0" 400"#),
        "the server's log has no line for GET /%00:\n{log_text}"
    );
    for word in ["Traceback", "Exception", "Error:"] {
        assert!(!log_text.contains(word), "the server's log holds {word}:\n{log_text}");
    }
    let _ = std::fs::remove_dir_all(&top);
}
