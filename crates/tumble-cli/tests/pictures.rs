//! `tumble view`, `export` and `plot` as a user runs them: the files they write, and clear errors
//! for bad input.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn tumble(args: &[&str], cwd: &Path) -> Output {
    Command::new(env!("CARGO_BIN_EXE_tumble")).args(args).current_dir(cwd).output().expect("tumble runs")
}

fn scene(name: &str) -> String {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../scenes").join(name);
    path.canonicalize().unwrap().to_str().unwrap().to_string()
}

fn text(bytes: &[u8]) -> String {
    String::from_utf8_lossy(bytes).into_owned()
}

/// Runs tumble expecting success; returns stdout.
fn ok(args: &[&str], cwd: &Path) -> String {
    let out = tumble(args, cwd);
    assert!(out.status.success(), "tumble {args:?} failed:\n{}", text(&out.stderr));
    text(&out.stdout)
}

/// Runs tumble expecting failure; returns stderr, which must be one clean `error:` message.
fn fails(args: &[&str], cwd: &Path) -> String {
    let out = tumble(args, cwd);
    assert!(!out.status.success(), "tumble {args:?} should fail");
    let stderr = text(&out.stderr);
    assert!(stderr.starts_with("error: "), "not a clean error: {stderr}");
    assert!(!stderr.contains("panicked"), "{stderr}");
    stderr
}

/// Width and height of a PNG, decoding the whole image.
fn png_size(path: &Path) -> (u32, u32) {
    let decoder = png::Decoder::new(std::io::BufReader::new(std::fs::File::open(path).unwrap()));
    let mut reader = decoder.read_info().expect("a PNG");
    let mut pixels = vec![0; reader.output_buffer_size()];
    let info = reader.next_frame(&mut pixels).expect("PNG pixels decode");
    // Not blank: a plot has lines and text in more than one colour.
    let distinct: std::collections::BTreeSet<&[u8]> =
        pixels.chunks(info.line_size / info.width as usize).collect();
    assert!(distinct.len() > 10, "the image is nearly blank");
    (info.width, info.height)
}

/// A short recording of the demo in `dir`.
fn demo_recording(dir: &Path) -> String {
    ok(&["run", &scene("demo.toml"), "--out", "demo.csv", "--duration", "5"], dir);
    dir.join("demo.csv").to_str().unwrap().to_string()
}

#[test]
fn plot_writes_a_png_of_the_expected_size() {
    let dir = tempfile::tempdir().unwrap();
    let csv = demo_recording(dir.path());
    let said = ok(&["plot", &csv, "-o", "omega.png", "--what", "omega:handle"], dir.path());
    assert!(said.contains("omega.png (1000x360)"), "{said}");
    assert_eq!(png_size(&dir.path().join("omega.png")), (1000, 360));

    // Several panels stack; --size sets the whole image.
    ok(
        &[
            "plot",
            &csv,
            "--scene",
            &scene("demo.toml"),
            "-o",
            "p/all.png",
            "--what",
            "energy,momentum,angular_momentum,omega_body",
        ],
        dir.path(),
    );
    assert_eq!(png_size(&dir.path().join("p/all.png")), (1000, 4 * 360));
    ok(
        &["plot", &scene("projectile.toml"), "-o", "e.png", "--what", "energy", "--size", "640x480"],
        dir.path(),
    );
    assert_eq!(png_size(&dir.path().join("e.png")), (640, 480));

    ok(&["plot", &csv, "-o", "omega.svg"], dir.path());
    let svg = std::fs::read_to_string(dir.path().join("omega.svg")).unwrap();
    assert!(svg.starts_with("<svg") && svg.contains("time (s)") && svg.contains("ω (rad/s)"));
}

#[test]
fn view_writes_one_self_contained_page() {
    let dir = tempfile::tempdir().unwrap();
    let said = ok(&["view", &scene("projectile.toml"), "-o", "page.html", "--fps", "30"], dir.path());
    assert!(said.contains("page.html (1 bodies, 49 frames"), "{said}");
    let page = std::fs::read_to_string(dir.path().join("page.html")).unwrap();
    assert!(page.starts_with("<!doctype html>"));
    assert!(page.contains("\"format\":\"tumble-viewer-1\""));
    // Nothing is loaded from elsewhere: no external scripts, styles or modules.
    for reference in ["<script src", "<link", "import(\"http", "from\"http"] {
        assert!(!page.contains(reference), "the page refers out: {reference}");
    }
    // A recording needs its scene; with it, it plays.
    let csv = demo_recording(dir.path());
    let err = fails(&["view", &csv], dir.path());
    assert!(err.contains("--scene"), "{err}");
    ok(&["view", &csv, "--scene", &scene("demo.toml"), "-o", "replay.html"], dir.path());
    assert!(dir.path().join("replay.html").exists());
}

#[test]
fn export_writes_glb() {
    let dir = tempfile::tempdir().unwrap();
    ok(&["export", &scene("demo.toml"), "-o", "demo.glb", "--duration", "1"], dir.path());
    let bytes = std::fs::read(dir.path().join("demo.glb")).unwrap();
    assert_eq!(&bytes[..4], b"glTF");
    let err = fails(&["export", &scene("demo.toml"), "-o", "demo.gltf"], dir.path());
    assert!(err.contains("*.glb"), "{err}");
}

#[test]
fn bad_input_gets_clear_errors() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let csv = demo_recording(d);

    let err = fails(&["plot", "missing.csv", "-o", "x.png"], d);
    assert!(err.contains("missing.csv") && err.contains("No such file"), "{err}");

    std::fs::write(d.join("corrupt.csv"), "t,body,px\n1,2,3\n").unwrap();
    let err = fails(&["plot", "corrupt.csv", "-o", "x.png"], d);
    assert!(err.contains("corrupt.csv:1") && err.contains("not a recording"), "{err}");

    let mut rows = std::fs::read_to_string(&csv).unwrap();
    rows.push_str("0.5,handle,0,0,zero,0,0,0,1,0,0,0,0,0,0\n");
    std::fs::write(d.join("bad_number.csv"), rows).unwrap();
    let err = fails(&["plot", "bad_number.csv", "-o", "x.png"], d);
    assert!(err.contains("bad_number.csv:") && err.contains("column pz: `zero` is not a number"), "{err}");

    std::fs::write(d.join("empty.csv"), format!("{}\n", tumble_io::RECORDING_HEADER)).unwrap();
    let err = fails(&["plot", "empty.csv", "-o", "x.png"], d);
    assert!(err.contains("no frames"), "{err}");

    let err = fails(&["plot", &csv, "-o", "x.png", "--what", "energy,spin"], d);
    assert!(err.contains("unknown --what `spin`") && err.contains("omega[:BODY]"), "{err}");
    let err = fails(&["plot", &csv, "-o", "x.png", "--what", "energy"], d);
    assert!(err.contains("masses") && err.contains("--scene"), "{err}");
    let err = fails(&["plot", &csv, "-o", "x.png", "--what", "omega:wheel"], d);
    assert!(err.contains("no body called \"wheel\"") && err.contains("handle"), "{err}");
    let err = fails(&["plot", &csv, "-o", "x.jpg"], d);
    assert!(err.contains("PNG or SVG"), "{err}");
    let err = fails(&["plot", &csv, "-o", "x.png", "--size", "big"], d);
    assert!(err.contains("WIDTHxHEIGHT"), "{err}");
    let err = fails(&["view", "scene.txt"], d);
    assert!(err.contains("expected a scene (.toml)"), "{err}");
    let err = fails(&["view", &csv, "--scene", &scene("projectile.toml")], d);
    assert!(err.contains("body \"handle\"") && err.contains("not in the scene"), "{err}");
    let err = fails(&["export", &scene("demo.toml"), "--scene", &scene("demo.toml")], d);
    assert!(err.contains("only for recordings"), "{err}");
    let err = fails(&["view", &scene("demo.toml"), "--fps", "0"], d);
    assert!(err.contains("--fps"), "{err}");
}
