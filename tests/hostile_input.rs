//! Careless and hostile input from the outside (issue 13): the same exit
//! code for the same mistake in every command, sizes beyond the machine
//! refused before the work, endless or special files refused fast, an
//! interrupt that leaves the folder as it was, the usual file permissions,
//! and every repair or impossible light said in a warning.

mod cli_support;
mod scene_support;

use cli_support::{assert_refused, names_in, stderr_lines};
use scene_support::builder::Doc;
use std::os::unix::fs::PermissionsExt;
use std::path::Path;
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};

fn lumlab() -> Command {
    Command::new(env!("CARGO_BIN_EXE_lumlab"))
}

/// Runs the command, killing it (and failing) when it takes longer than
/// `limit`: an endless read must not hang the suite.
fn run_within(command: &mut Command, limit: Duration) -> Output {
    let mut child = command
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("lumlab runs");
    let start = Instant::now();
    while child.try_wait().expect("waiting").is_none() {
        if start.elapsed() > limit {
            let _ = child.kill();
            panic!("{command:?} still running after {limit:?}");
        }
        std::thread::sleep(Duration::from_millis(20));
    }
    child.wait_with_output().expect("output")
}

fn run(args: &[&str]) -> Output {
    run_within(lumlab().args(args), Duration::from_secs(120))
}

fn mode(path: &Path) -> u32 {
    std::fs::metadata(path).unwrap().permissions().mode() & 0o777
}

#[test]
fn the_same_mistake_gets_the_same_answer_from_every_command() {
    let dir = tempfile::tempdir().unwrap();
    let path = |name: &str| dir.path().join(name).to_str().unwrap().to_owned();
    for command in ["render", "reference"] {
        assert_refused(&run(&[command, "--out", &path("a.jpg")]), 2, ".png or .exr");
        assert_refused(&run(&[command, "--out", &path("no/a.png")]), 2, "does not exist");
        assert_refused(&run(&[command, "--size", "8x8"]), 2, "--out");
        assert_refused(&run(&[command, "--k", "2", "--out", &path("a.png")]), 2, "--k");
    }
    assert_refused(&run(&["report", "--size", "8x8"]), 2, "--out");
    // A bad output is named before a long reference would start.
    let start = Instant::now();
    let slow = [
        "--size",
        "640x360",
        "--light-radius",
        "0.3",
        "--light-samples",
        "4096",
        "--yes",
    ];
    let out = run(&[&["reference"][..], &slow, &["--out", &path("no/a.png")]].concat());
    assert_refused(&out, 2, "does not exist");
    assert!(start.elapsed() < Duration::from_secs(10), "{:?}", start.elapsed());
    assert!(names_in(dir.path()).is_empty());
}

#[test]
fn sizes_beyond_the_machine_are_one_line_not_a_panic() {
    let dir = tempfile::tempdir().unwrap();
    let png = dir.path().join("big.png");
    let png = png.to_str().unwrap();
    assert_refused(
        &run(&["render", "--size", "16384x16384", "--out", png]),
        2,
        "--size 16384x16384",
    );
    let huge = [
        "reference",
        "--size",
        "16384x16384",
        "--spp",
        "65536",
        "--yes",
        "--out",
        png,
    ];
    assert_refused(&run(&huge), 2, "lower --size");
    let dear = ["reference", "--size", "4000x4000", "--spp", "1024", "--out", png];
    assert_refused(&run(&dear), 2, "--yes");
    assert!(names_in(dir.path()).is_empty());
}

#[test]
fn endless_and_special_files_are_refused_at_once() {
    let dir = tempfile::tempdir().unwrap();
    let png = dir.path().join("a.png");
    let png = png.to_str().unwrap();
    let fast = Duration::from_secs(30);
    for flag in ["--scene", "--settings"] {
        let out = run_within(
            lumlab().args(["reference", flag, "/dev/zero", "--out", png]),
            fast,
        );
        assert_refused(&out, 1, "not a regular file");
    }
    let sweep = ["report", "--sweep", "/dev/zero", "--out", png];
    assert_refused(&run_within(lumlab().args(sweep), fast), 1, "not a regular file");

    // A buffer URI that climbs to a device.
    let mut json: serde_json::Value = serde_json::from_slice(&Doc::square().gltf_embedded()).unwrap();
    json["buffers"][0]["uri"] = format!("{}dev/zero", "../".repeat(32)).into();
    let scene = dir.path().join("device.gltf");
    std::fs::write(&scene, serde_json::to_vec(&json).unwrap()).unwrap();
    let out = run_within(lumlab().args(["info", "--scene", scene.to_str().unwrap()]), fast);
    assert_refused(&out, 1, "not a regular file");

    // A settings file of 64 MiB (sparse: no disk) stops at the 1 MiB limit.
    let big = dir.path().join("big.toml");
    std::fs::File::create(&big).unwrap().set_len(64 << 20).unwrap();
    let out = run_within(
        lumlab().args(["reference", "--settings", big.to_str().unwrap(), "--out", png]),
        fast,
    );
    assert_refused(&out, 1, "1 MiB limit");
    assert_eq!(names_in(dir.path()), ["big.toml", "device.gltf"]);
}

#[test]
fn an_interrupted_report_leaves_the_folder_as_it_was() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("notes.txt"), "mine").unwrap();
    let before = names_in(dir.path());
    let out = dir.path().join("report");
    // A reference of several seconds: the interrupt lands in the middle.
    let mut child = lumlab()
        .args([
            "report",
            "--size",
            "320x180",
            "--light-radius",
            "0.3",
            "--light-samples",
            "256",
        ])
        .args(["--out", out.to_str().unwrap()])
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let start = Instant::now();
    while !names_in(dir.path())
        .iter()
        .any(|n| n.contains("lumlab-report-partial"))
    {
        assert!(
            child.try_wait().unwrap().is_none(),
            "the report ended before the interrupt"
        );
        assert!(
            start.elapsed() < Duration::from_secs(60),
            "no staging folder appeared"
        );
        std::thread::sleep(Duration::from_millis(20));
    }
    std::thread::sleep(Duration::from_millis(300));
    let killed = Command::new("kill")
        .args(["-INT", &child.id().to_string()])
        .status()
        .unwrap();
    assert!(killed.success());
    let stop = Instant::now();
    let output = child.wait_with_output().unwrap();
    assert!(
        stop.elapsed() < Duration::from_secs(20),
        "slow to stop: {:?}",
        stop.elapsed()
    );
    assert_eq!(output.status.code(), Some(130), "{:?}", stderr_lines(&output));
    assert_eq!(names_in(dir.path()), before);
}

#[test]
fn outputs_get_the_permissions_any_program_gives_them() {
    let dir = tempfile::tempdir().unwrap();
    let png = dir.path().join("a.png");
    let shown = png.to_str().unwrap();
    let under_umask_022 = |out: &str| {
        let script = format!("umask 022 && exec \"$0\" reference --size 16x9 --out '{out}'");
        let out = run_within(
            Command::new("sh").args(["-c", &script, env!("CARGO_BIN_EXE_lumlab")]),
            Duration::from_secs(60),
        );
        assert!(out.status.success(), "{:?}", stderr_lines(&out));
    };
    under_umask_022(shown);
    assert_eq!(mode(&png), 0o644);
    std::fs::set_permissions(&png, std::fs::Permissions::from_mode(0o640)).unwrap();
    under_umask_022(shown);
    assert_eq!(mode(&png), 0o640, "an existing file keeps its mode");

    std::fs::set_permissions(&png, std::fs::Permissions::from_mode(0o444)).unwrap();
    let before = std::fs::read(&png).unwrap();
    assert_refused(
        &run(&["reference", "--size", "16x9", "--out", shown]),
        2,
        "read-only",
    );
    assert_eq!(std::fs::read(&png).unwrap(), before);

    // Through a link: the link stays, its target is written.
    let link = dir.path().join("link.png");
    std::os::unix::fs::symlink("target.png", &link).unwrap();
    let out = run(&["reference", "--size", "16x9", "--out", link.to_str().unwrap()]);
    assert!(out.status.success(), "{:?}", stderr_lines(&out));
    assert!(std::fs::symlink_metadata(&link).unwrap().file_type().is_symlink());
    assert_eq!(image::open(dir.path().join("target.png")).unwrap().width(), 16);
    assert_eq!(names_in(dir.path()), ["a.png", "link.png", "target.png"]);
}

#[test]
fn repairs_and_impossible_lights_are_said() {
    let dir = tempfile::tempdir().unwrap();
    let png = dir.path().join("a.png");
    let png = png.to_str().unwrap();
    let cutting = ["--size", "16x9", "--light", "0,0.1,0", "--light-radius", "0.5"];
    let refused = run(&[&["reference"][..], &cutting, &["--out", png]].concat());
    assert_refused(&refused, 2, "cuts through 'ground'");
    for command in ["reference", "render"] {
        let out = run(&[&[command][..], &cutting, &["--allow-impossible", "--out", png]].concat());
        assert!(out.status.success(), "{command}: {:?}", stderr_lines(&out));
        let warned = stderr_lines(&out)
            .iter()
            .any(|l| l.starts_with("lumlab: warning: the sphere light"));
        assert!(warned, "{command}: {:?}", stderr_lines(&out));
    }

    // A zero-area triangle beside a good square: dropped, and said.
    let (mut doc, _) = Doc::simple(
        &[
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [1.0, 1.0, 0.0],
            [0.0, 1.0, 0.0],
            [2.0, 2.0, 2.0],
        ],
        None,
        4,
    );
    let indices = doc.indices(&[0, 1, 2, 0, 2, 3, 4, 4, 4], 5125);
    doc.json["meshes"][0]["primitives"][0]["indices"] = indices.into();
    let scene = doc.write_external(dir.path(), "repaired");
    let view = ["--camera", "0.5,0.5,3:0.5,0.5,0:45", "--light", "0.5,0.5,2"];
    let out = run(&[
        &["reference", "--size", "16x9", "--scene", scene.to_str().unwrap()][..],
        &view,
        &["--out", png],
    ]
    .concat());
    assert!(out.status.success(), "{:?}", stderr_lines(&out));
    assert!(
        stderr_lines(&out)
            .iter()
            .any(|l| l.starts_with("lumlab: warning:")),
        "{:?}",
        stderr_lines(&out)
    );
}
