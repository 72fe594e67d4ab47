//! Remote viewing: Rerun's web viewer served by `--serve-web` shows the scene in headless
//! Chromium, and a viewer that goes away mid-session leaves the session working and the
//! file whole.

use std::io::{BufRead as _, BufReader, Write as _};
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};

use drape::viz::replay::{FlatChunk, first_difference, read_rrd};

/// A TCP port nobody listens on now (the OS picks it).
fn free_port() -> u16 {
    std::net::TcpListener::bind("127.0.0.1:0")
        .and_then(|l| l.local_addr())
        .map(|a| a.port())
        .expect("a free port")
}

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("drape-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// Starts `drape ARGS` and waits until it says it is serving late viewers; returns the
/// child and what it printed.
fn serving(args: &[&str]) -> (Child, String) {
    let mut child = super::common::drape_cli()
        .args(args)
        .stdout(Stdio::piped())
        .stderr(Stdio::null())
        .spawn()
        .expect("drape starts");
    let stdout = child.stdout.take().expect("stdout");
    let mut printed = String::new();
    for line in BufReader::new(stdout).lines() {
        let line = line.expect("utf-8");
        printed.push_str(&line);
        printed.push('\n');
        if line.contains("still serving") {
            return (child, printed);
        }
    }
    child.kill().ok();
    child.wait().ok();
    panic!("drape never said it was serving: {printed}");
}

/// `drape run --serve-web` on two free ports, saving into `file`, started and serving:
/// the child, what it printed, and the gRPC and HTTP ports.
fn serving_web(file: &Path) -> (Child, String, u16, u16) {
    let (grpc, web) = (free_port(), free_port());
    let (child, printed) = serving(&[
        "run",
        "--serve-web",
        "--port",
        &grpc.to_string(),
        "--web-port",
        &web.to_string(),
        "--save",
        file.to_str().expect("a UTF-8 path"),
    ]);
    (child, printed, grpc, web)
}

fn interrupt(child: &mut Child) -> Option<i32> {
    Command::new("kill")
        .args(["-INT", &child.id().to_string()])
        .status()
        .expect("kill runs");
    child.wait().expect("drape ends").code()
}

/// The Python with Playwright that `scripts/setup-browser` prepares.
fn browser_python() -> PathBuf {
    std::env::var_os("DRAPE_TOOLS_PYTHON").map_or_else(|| super::common::tools_venv().join("bin/python"), PathBuf::from)
}

/// The web viewer drape serves, opened in Debian's Chromium (headless, software WebGL),
/// shows the demo's scene: the 3D views hold the strongly coloured garment and body that an
/// empty viewer does not (`scripts/web_check.py`; its docstring gives the measure). Then
/// Ctrl-C stops the server and the file holds the same data as a plain run.
#[test]
fn the_web_viewer_served_by_drape_shows_the_scene_in_headless_chromium() {
    let python = browser_python();
    assert!(
        python.exists() && Path::new("/usr/bin/chromium").exists(),
        "the browser test needs Chromium and Playwright: run scripts/setup-browser (the README's \
         test command does), or set DRAPE_TOOLS_PYTHON to a Python with playwright"
    );
    let dir = scratch("web");
    let served = dir.join("served.rrd");
    let (mut child, printed, grpc, web) = serving_web(&served);
    assert!(printed.contains(&format!(":{web}/?url=rerun%2Bhttp://")), "{printed}");
    let url = format!("http://localhost:{web}/?url=rerun%2Bhttp://localhost:{grpc}/proxy");
    let shot = dir.join("web.png");
    let check = Command::new(&python)
        .arg(concat!(env!("CARGO_MANIFEST_DIR"), "/scripts/web_check.py"))
        .args([url.as_str(), shot.to_str().unwrap()])
        .output()
        .expect("the browser check runs");
    let report = String::from_utf8_lossy(&check.stdout);
    let code = interrupt(&mut child);
    assert!(
        check.status.success(),
        "the browser never showed the scene (screenshot {}): {report}{}",
        shot.display(),
        String::from_utf8_lossy(&check.stderr)
    );
    assert_eq!(code, Some(0));
    let plain = dir.join("plain.rrd");
    let out = super::common::drape_cli()
        .args(["run", "--save", plain.to_str().unwrap()])
        .output()
        .expect("drape runs");
    assert!(out.status.success());
    assert_eq!(first_difference(&data(&plain), &data(&served), 0.0), None);
    std::fs::remove_dir_all(&dir).ok();
}

fn data(path: &Path) -> Vec<FlatChunk> {
    read_rrd(path)
        .unwrap_or_else(|e| panic!("{}: {e}", path.display()))
        .into_iter()
        .filter(|c| !c.entity.starts_with("/__"))
        .collect()
}

/// `drape edit --connect` to a viewer (here a drape server, which takes writes like any
/// Rerun proxy) that is killed after the first steps: the remaining lines still run, and the
/// file holds exactly what the same lines log with no viewer at all.
#[test]
fn a_viewer_that_goes_away_mid_edit_loses_nothing_from_the_file() {
    let dir = scratch("viewer-gone");
    let port = free_port();
    let empty = dir.join("empty.drape");
    std::fs::write(&empty, "drape 1\n").unwrap();
    let (mut viewer, _) = serving(&[
        "run",
        empty.to_str().unwrap(),
        "--serve",
        "--port",
        &port.to_string(),
        "--save",
        dir.join("viewer.rrd").to_str().unwrap(),
    ]);
    let first = "garment jumpsuit fit=tight resolution=3\nset ease 0.008\n";
    let rest = "drag waist.front by=0,0,-0.01\nundo\nset waist_girth +0.02\nquit\n";
    let live = dir.join("live.rrd");
    let url = format!("rerun+http://127.0.0.1:{port}/proxy");
    let mut edit = super::common::drape_cli()
        .args(["edit", "--connect", &url, "--save", live.to_str().unwrap()])
        .stdin(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("drape edit starts");
    let mut stdin = edit.stdin.take().expect("stdin");
    stdin.write_all(first.as_bytes()).unwrap();
    stdin.flush().unwrap();
    std::thread::sleep(std::time::Duration::from_secs(2));
    viewer.kill().expect("the viewer goes away");
    viewer.wait().ok();
    stdin.write_all(rest.as_bytes()).unwrap();
    drop(stdin);
    let out = edit.wait_with_output().expect("drape edit ends");
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(0), "{stderr}");
    assert!(stderr.contains("step 5 set"), "the last line ran: {stderr}");

    let alone = dir.join("alone.rrd");
    let mut edit = super::common::drape_cli()
        .args(["edit", "--save", alone.to_str().unwrap()])
        .stdin(Stdio::piped())
        .stderr(Stdio::null())
        .spawn()
        .expect("drape edit starts");
    edit.stdin
        .take()
        .expect("stdin")
        .write_all(format!("{first}{rest}").as_bytes())
        .unwrap();
    assert!(edit.wait().expect("drape edit ends").success());
    let (a, b) = (data(&alone), data(&live));
    assert!(a.len() > 100, "{} chunks", a.len());
    assert_eq!(first_difference(&a, &b, 0.0), None);
    std::fs::remove_dir_all(&dir).ok();
}

/// The addresses the kernel says listen on `ports`, from its socket tables (`/proc/net/tcp`
/// and `tcp6`): the truth from outside drape.
fn listening_on(ports: &[u16]) -> Vec<(std::net::IpAddr, u16)> {
    let mut out = Vec::new();
    for (table, v6) in [("/proc/net/tcp", false), ("/proc/net/tcp6", true)] {
        let Ok(text) = std::fs::read_to_string(table) else {
            assert!(v6, "{table} is missing: this test reads the kernel's socket table");
            continue;
        };
        for line in text.lines().skip(1) {
            let f: Vec<&str> = line.split_whitespace().collect();
            // Field 3 is the state: 0A is LISTEN.
            let (Some(local), Some(&"0A")) = (f.get(1), f.get(3)) else {
                continue;
            };
            let Some((ip, port)) = local.split_once(':') else {
                continue;
            };
            let port = u16::from_str_radix(port, 16).expect("a hex port");
            if !ports.contains(&port) {
                continue;
            }
            // The address is in the kernel's byte order, 32 bits at a time.
            let words: Vec<u32> = (0..ip.len() / 8)
                .map(|k| {
                    u32::from_str_radix(&ip[8 * k..8 * k + 8], 16)
                        .expect("hex")
                        .swap_bytes()
                })
                .collect();
            let ip = if v6 {
                let bytes: Vec<u8> = words.iter().flat_map(|w| w.to_be_bytes()).collect();
                std::net::IpAddr::from(<[u8; 16]>::try_from(bytes.as_slice()).expect("16 bytes"))
            } else {
                std::net::IpAddr::from(words[0].to_be_bytes())
            };
            out.push((ip, port));
        }
    }
    out.sort();
    out
}

/// `--serve-web` listens on this machine only unless told otherwise: both its servers (gRPC
/// and HTTP) on 127.0.0.1, as the kernel's socket table shows; `--bind 0.0.0.0` opens the
/// gRPC server to every network, with a warning that Rerun's servers have no
/// authentication.
#[test]
fn servers_listen_on_this_machine_only_unless_bound_elsewhere() {
    let dir = scratch("bind");
    let (mut child, printed, grpc, web) = serving_web(&dir.join("local.rrd"));
    let local = listening_on(&[grpc, web]);
    interrupt(&mut child);
    let loopback = std::net::IpAddr::from([127, 0, 0, 1]);
    let mut want = vec![(loopback, grpc), (loopback, web)];
    want.sort();
    assert_eq!(local, want, "{printed}");
    assert!(
        printed.contains("this machine only") && printed.contains("ssh -L"),
        "{printed}"
    );

    let port = free_port();
    let mut child = super::common::drape_cli()
        .args([
            "run",
            "--serve",
            "--bind",
            "0.0.0.0",
            "--port",
            &port.to_string(),
            "--save",
        ])
        .arg(dir.join("open.rrd"))
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("drape starts");
    let stdout = BufReader::new(child.stdout.take().expect("stdout"));
    for line in stdout.lines() {
        if line.expect("utf-8").contains("still serving") {
            break;
        }
    }
    let open = listening_on(&[port]);
    interrupt(&mut child);
    let mut warned = String::new();
    std::io::Read::read_to_string(&mut child.stderr.take().expect("stderr"), &mut warned).ok();
    assert_eq!(open, vec![(std::net::IpAddr::from([0, 0, 0, 0]), port)]);
    assert!(warned.contains("no authentication"), "{warned}");
    std::fs::remove_dir_all(&dir).ok();
}
