//! Running the `render` example from tests: built once, run with arguments, its
//! outputs read back.

use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};
use std::sync::Once;
use std::time::{Duration, Instant};

use embedded_graphics::pixelcolor::Rgb888;
use embedded_graphics_simulator::SimulatorDisplay;

/// The render example, built once (in the test profile, beside this test binary).
pub fn render_bin() -> PathBuf {
    static BUILD: Once = Once::new();
    example_bin("render", &BUILD)
}

/// Example `name`, built once by `once` in this test binary's profile (`target/debug`,
/// `target/release` or a named profile's directory: the one this binary runs from), so
/// that `cargo test --release` runs release builds of the examples, not stale ones.
pub fn example_bin(name: &str, once: &Once) -> PathBuf {
    let exe = std::env::current_exe().unwrap();
    let dir = exe.parent().unwrap().parent().unwrap();
    let bin = dir
        .join("examples")
        .join(format!("{name}{}", std::env::consts::EXE_SUFFIX));
    once.call_once(|| {
        let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".into());
        let mut args = vec!["build", "--quiet", "--example", name];
        let profile = dir.file_name().and_then(|p| p.to_str()).unwrap_or("debug");
        match profile {
            "debug" => {}
            "release" => args.push("--release"),
            other => args.extend(["--profile", other]),
        }
        let status = Command::new(cargo)
            .args(&args)
            .current_dir(env!("CARGO_MANIFEST_DIR"))
            .status()
            .unwrap();
        assert!(status.success());
    });
    bin
}

pub fn tmp(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("zraster-cli-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir.join(name)
}

pub fn render(args: &[&str]) -> Output {
    Command::new(render_bin()).args(args).output().unwrap()
}

/// `render args`, failing the test if it has not finished within `secs` seconds (it is
/// killed): for inputs that used to hang or read without end.
pub fn render_within(secs: u64, args: &[&str]) -> Output {
    let mut child = Command::new(render_bin())
        .args(args)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let start = Instant::now();
    while child.try_wait().unwrap().is_none() {
        if start.elapsed() > Duration::from_secs(secs) {
            let _ = child.kill();
            let _ = child.wait();
            panic!("{args:?}: still running after {secs} s");
        }
        std::thread::sleep(Duration::from_millis(20));
    }
    child.wait_with_output().unwrap()
}

pub fn run_ok(args: &[&str]) -> String {
    let out = render(args);
    assert!(
        out.status.success(),
        "{args:?}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8(out.stdout).unwrap()
}

pub fn load(path: &Path) -> SimulatorDisplay<Rgb888> {
    SimulatorDisplay::load_png(path).unwrap()
}

pub fn write(name: &str, text: &[u8]) -> String {
    let p = tmp(name);
    std::fs::write(&p, text).unwrap();
    p.to_str().unwrap().to_string()
}

pub fn fails_with(args: &[&str], needle: &str) {
    let out = render(args);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
    assert!(
        err.contains(needle),
        "{args:?}: stderr {err:?} lacks {needle:?}"
    );
}
