//! Nothing lost, nothing clobbered: an output that is a device or a FIFO is written, never
//! replaced by a regular file, and its errors are reported; the reader of stdout going away is
//! not an error; a bad row of a batch comes after the rows before it.

mod common;
use common::*;
use std::io::Read;
use std::os::unix::fs::FileTypeExt;
use std::path::{Path, PathBuf};
use std::process::{Command as Process, Stdio};

fn s(p: &Path) -> &str {
    p.to_str().unwrap()
}

/// A fresh, empty directory for one test.
fn fresh_dir(name: &str) -> PathBuf {
    let dir = tmp(name);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// A character device `major,minor` at `path` (a copy of /dev/null is 1,3, of /dev/full 1,7);
/// `false` when the system does not let us make one (not root).
fn char_device(path: &Path, major: u32, minor: u32) -> bool {
    let made = Process::new("mknod")
        .args([s(path), "c", &major.to_string(), &minor.to_string()])
        .stderr(Stdio::null())
        .status()
        .is_ok_and(|st| st.success());
    if !made {
        eprintln!("skipped: cannot make a device node with mknod (not root?)");
    }
    made
}

fn is_char_device(path: &Path) -> bool {
    std::fs::symlink_metadata(path)
        .unwrap()
        .file_type()
        .is_char_device()
}

/// The commands that write an output file, each writing to `target` (whose name gives the
/// extension the command needs).
fn writers(target: &Path) -> Vec<Vec<String>> {
    let t = s(target).to_string();
    let cmds: Vec<Vec<&str>> = vec![
        vec!["export", "builtin:ur5", "--to", "urdf", "--output", &t],
        vec![
            "simulate",
            "builtin:planar2",
            "--duration",
            "0.5",
            "--output",
            &t,
        ],
        vec!["view", "builtin:planar2", "--output", &t],
    ];
    cmds.into_iter()
        .map(|c| c.into_iter().map(String::from).collect())
        .collect()
}

#[test]
fn a_null_device_stays_a_device() {
    let dir = fresh_dir("out-null");
    for (name, cmd) in [("null.urdf", 0), ("null.csv", 1), ("null.html", 2)] {
        let dev = dir.join(name);
        if !char_device(&dev, 1, 3) {
            return;
        }
        let args = writers(&dev).swap_remove(cmd);
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        ok(&args);
        assert!(is_char_device(&dev), "{args:?} replaced the device");
        // Nothing but the device in the directory: no temporary file left beside it.
        let left: Vec<_> = std::fs::read_dir(&dir).unwrap().collect();
        assert_eq!(left.len(), 1, "{args:?}");
        std::fs::remove_file(&dev).unwrap();
    }
    // The plots of simulate and torque-profile too (drawn aside, then copied).
    let dev = dir.join("null.svg");
    if !char_device(&dev, 1, 3) {
        return;
    }
    ok(&[
        "simulate",
        "builtin:planar2",
        "--duration",
        "0.2",
        "--plot",
        s(&dev),
    ]);
    ok(&[
        "torque-profile",
        "builtin:planar2",
        "--trajectory",
        "quintic",
        "--qf",
        "1,1",
        "--duration",
        "1",
        "--plot",
        s(&dev),
    ]);
    assert!(is_char_device(&dev));
}

#[test]
fn a_full_device_reports_the_full_disk() {
    let dir = fresh_dir("out-full");
    for (name, cmd) in [("full.urdf", 0), ("full.csv", 1), ("full.html", 2)] {
        let dev = dir.join(name);
        if !char_device(&dev, 1, 7) {
            return;
        }
        let args = writers(&dev).swap_remove(cmd);
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        let err = fails(&args, "No space left on device");
        assert!(err.contains(s(&dev)), "the error names the path: {err}");
        assert!(is_char_device(&dev), "{args:?} replaced the device");
        std::fs::remove_file(&dev).unwrap();
    }
    let dev = dir.join("full.json");
    if !char_device(&dev, 1, 7) {
        return;
    }
    fails(
        &[
            "torque-profile",
            "builtin:planar2",
            "--trajectory",
            "quintic",
            "--qf",
            "1,1",
            "--duration",
            "1",
            "--output",
            s(&dev),
        ],
        "No space left on device",
    );
}

#[test]
fn a_fifo_reader_receives_the_output() {
    let dir = fresh_dir("out-fifo");
    for (name, cmd) in [("pipe.urdf", 0), ("pipe.csv", 1), ("pipe.html", 2)] {
        let fifo = dir.join(name);
        let made = Process::new("mkfifo")
            .arg(s(&fifo))
            .status()
            .is_ok_and(|st| st.success());
        if !made {
            eprintln!("skipped: mkfifo failed");
            return;
        }
        let reader = {
            let fifo = fifo.clone();
            std::thread::spawn(move || {
                let mut text = String::new();
                std::fs::File::open(&fifo)
                    .unwrap()
                    .read_to_string(&mut text)
                    .unwrap();
                text
            })
        };
        let args = writers(&fifo).swap_remove(cmd);
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        ok(&args);
        let text = reader.join().unwrap();
        let expected_start = ["<?xml", "t,", "<!DOCTYPE html>"][cmd];
        assert!(text.starts_with(expected_start), "{args:?}: {:.40}", text);
        let ft = std::fs::symlink_metadata(&fifo).unwrap().file_type();
        assert!(ft.is_fifo(), "{args:?} replaced the FIFO");
        // The same output as written to a regular file.
        let file = dir.join(format!("file.{}", name.rsplit('.').next().unwrap()));
        let args = writers(&file).swap_remove(cmd);
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        ok(&args);
        if cmd != 2 {
            assert_eq!(std::fs::read_to_string(&file).unwrap(), text, "{args:?}");
        }
    }
}

#[test]
fn a_reader_going_away_ends_a_streamed_run_quietly() {
    for cmd in [
        vec![
            "simulate",
            "builtin:ur5",
            "--duration",
            "20",
            "--format",
            "csv",
        ],
        vec![
            "simulate",
            "builtin:ur5",
            "--duration",
            "20",
            "--format",
            "json",
        ],
    ] {
        let mut child = Process::new(env!("CARGO_BIN_EXE_screwdyn"))
            .args(&cmd)
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
            .unwrap();
        let mut out = child.stdout.take().unwrap();
        let mut first = [0u8; 10];
        out.read_exact(&mut first).unwrap();
        drop(out);
        let result = child.wait_with_output().unwrap();
        let err = String::from_utf8_lossy(&result.stderr);
        assert_eq!(result.status.code(), Some(0), "{cmd:?}: {err}");
        // Nothing but the run's warnings (the UR5's wrist reaches its limit stops; the JSON
        // run is written whole at its end, so the run is over when the reader goes away).
        let other = err.lines().find(|l| !l.starts_with("screwdyn: warning: "));
        assert_eq!(other, None, "{cmd:?}: {err}");
    }
}

#[test]
fn closed_standard_descriptors_do_not_receive_an_output() {
    // Started with stdin, stdout and stderr closed, the program reopens them onto /dev/null
    // before it opens anything, as the standard library's start-up does (otherwise its own
    // files would get descriptors 0–2, and the report or a warning could land in one of them):
    // it succeeds and writes the run file it writes with them open.
    let dir = fresh_dir("closed-descriptors");
    let (open, closed) = (dir.join("open.csv"), dir.join("closed.csv"));
    fn run(out: &Path) -> Vec<&str> {
        vec![
            "simulate",
            "builtin:ur5",
            "--duration",
            "0.01",
            "--output",
            s(out),
            "--format",
            "json",
        ]
    }
    let reference = Process::new(env!("CARGO_BIN_EXE_screwdyn"))
        .args(run(&open))
        .output()
        .unwrap();
    assert!(reference.status.success());
    let script = format!("exec <&- >&- 2>&-; exec \"$0\" {}", run(&closed).join(" "));
    let status = Process::new("sh")
        .args(["-c", &script, env!("CARGO_BIN_EXE_screwdyn")])
        .status()
        .unwrap();
    assert_eq!(status.code(), Some(0));
    assert_eq!(
        std::fs::read_to_string(&closed).unwrap(),
        std::fs::read_to_string(&open).unwrap()
    );
    assert!(others(&dir, "open.csv").iter().all(|f| f == "closed.csv"));
}

/// `rnea --format csv` on `text` (header and rows of q.shoulder_pan_joint): stdout, stderr and
/// the exit status.
fn rnea_rows(name: &str, text: &str) -> (String, String, Option<i32>) {
    let p = tmp(name);
    std::fs::write(&p, text).unwrap();
    let out = bin()
        .args(["rnea", "builtin:ur5", "--input", s(&p), "--format", "csv"])
        .output()
        .unwrap();
    (
        String::from_utf8(out.stdout).unwrap(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
        out.status.code(),
    )
}

#[test]
fn rows_before_a_bad_row_are_written() {
    // Row 3 (line 4) is bad: rows 1 and 2 come out, with the header, then the error.
    let (out, err, code) = rnea_rows("bad_third.csv", "q.shoulder_pan_joint\n0.1\n0.2\nx1\n");
    assert_eq!(code, Some(2), "{err}");
    assert!(
        err.contains("bad_third.csv:4:") && err.contains("'x1'"),
        "{err}"
    );
    let lines: Vec<&str> = out.lines().collect();
    assert_eq!(lines.len(), 3, "{out}");
    assert!(lines[0].starts_with("tau."), "{out}");
    // The rows are those of the good file alone.
    let (good, _, code) = rnea_rows("good_two.csv", "q.shoulder_pan_joint\n0.1\n0.2\n");
    assert_eq!(code, Some(0));
    assert_eq!(out, good);

    // 10 000 rows with a bad one at row k = 5000, in the middle of a chunk of 256 rows: exactly
    // k − 1 data rows come out.
    let k = 5000;
    let mut text = String::from("q.shoulder_pan_joint\n");
    for i in 1..=10_000 {
        if i == k {
            text.push_str("nope\n");
        } else {
            text.push_str(&format!("{}\n", i as f64 * 1e-4));
        }
    }
    let (out, err, code) = rnea_rows("bad_middle.csv", &text);
    assert_eq!(code, Some(2), "{err}");
    assert!(err.contains(&format!("bad_middle.csv:{}:", k + 1)), "{err}");
    assert_eq!(out.lines().count(), 1 + (k - 1), "header and k − 1 rows");
    // The last row written is row k − 1's.
    let (last, _, _) = rnea_rows(
        "row_before.csv",
        &format!("q.shoulder_pan_joint\n{}\n", (k - 1) as f64 * 1e-4),
    );
    assert_eq!(out.lines().last(), last.lines().nth(1));
}

#[test]
fn a_file_size_limit_is_an_error_not_a_signal() {
    // No `trap '' XFSZ` here: the program ignores SIGXFSZ itself, so the write fails with
    // EFBIG, the previous file stays and the temporary file is removed.
    let dir = fresh_dir("out-limit");
    let run = dir.join("run.csv");
    std::fs::write(&run, "previous run\n").unwrap();
    let out = Process::new("sh")
        .arg("-c")
        .arg(format!(
            "ulimit -f 8; exec {} simulate builtin:ur5 --duration 0.2 --output {}",
            env!("CARGO_BIN_EXE_screwdyn"),
            s(&run)
        ))
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(
        err.contains("cannot write") && err.contains("run.csv"),
        "{err}"
    );
    assert_eq!(std::fs::read(&run).unwrap(), b"previous run\n");
    let left: Vec<_> = std::fs::read_dir(&dir).unwrap().collect();
    assert_eq!(left.len(), 1, "no temporary file is left");
}

/// The names in `dir` other than `keep`.
fn others(dir: &Path, keep: &str) -> Vec<String> {
    std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n != keep)
        .collect()
}

#[test]
fn sigterm_and_sigint_remove_the_unfinished_output() {
    for (signal, code) in [("TERM", 143), ("INT", 130)] {
        let dir = fresh_dir(&format!("signal-{signal}"));
        let run = dir.join("run.csv");
        std::fs::write(&run, "old\n").unwrap();
        let mut child = Process::new(env!("CARGO_BIN_EXE_screwdyn"))
            .args([
                "simulate",
                "builtin:ur5",
                "--duration",
                "5000",
                "--output",
                s(&run),
            ])
            .stdout(Stdio::null())
            .stderr(Stdio::piped())
            .spawn()
            .unwrap();
        // Wait until the temporary file is being written.
        let deadline = std::time::Instant::now() + std::time::Duration::from_secs(30);
        while others(&dir, "run.csv").is_empty() {
            assert!(
                std::time::Instant::now() < deadline,
                "no temporary file appeared"
            );
            std::thread::sleep(std::time::Duration::from_millis(20));
        }
        let sent = Process::new("kill")
            .args([&format!("-{signal}"), &child.id().to_string()])
            .status()
            .unwrap();
        assert!(sent.success());
        let status = child.wait().unwrap();
        let mut err = String::new();
        child
            .stderr
            .take()
            .unwrap()
            .read_to_string(&mut err)
            .unwrap();
        assert_eq!(status.code(), Some(code), "SIG{signal}: {err}");
        assert!(
            err.contains(&format!("stopped by SIG{signal}; removed the unfinished")),
            "{err}"
        );
        assert_eq!(std::fs::read_to_string(&run).unwrap(), "old\n");
        assert!(
            others(&dir, "run.csv").is_empty(),
            "{:?}",
            others(&dir, "run.csv")
        );
    }
}

#[test]
fn a_temporary_file_left_by_a_killed_writer_is_removed_by_the_next_write() {
    // SIGKILL cannot be caught: its temporary file stays until the next write to the same
    // path, which removes ours whose process is gone (and nobody else's).
    let dir = fresh_dir("stale-temporary");
    let run = dir.join("run.csv");
    let stale = dir.join(".run.csv.999999999.AbCdEf.csv");
    let foreign = dir.join(".run.csv.notes.csv");
    std::fs::write(&stale, "partial").unwrap();
    std::fs::write(&foreign, "someone else's").unwrap();
    ok(&[
        "simulate",
        "builtin:planar2",
        "--duration",
        "0.01",
        "--output",
        s(&run),
    ]);
    assert!(!stale.exists());
    assert!(foreign.exists());
    assert!(run.exists());
}

#[test]
fn a_plot_that_cannot_be_drawn_leaves_the_complete_run() {
    // docs/cli.md, Output files: each output stands on its own.
    let dir = fresh_dir("plot-fails");
    let run = dir.join("run.csv");
    std::fs::write(&run, "old\n").unwrap();
    let plot = dir.join("no-such-dir").join("p.png");
    let e = fails(
        &[
            "simulate",
            "builtin:planar2",
            "--duration",
            "0.1",
            "--output",
            s(&run),
            "--plot",
            s(&plot),
        ],
        "cannot write",
    );
    assert!(e.contains("p.png"), "{e}");
    let text = std::fs::read_to_string(&run).unwrap();
    assert!(text.starts_with("t,q.joint1,"), "{text}");
    assert_eq!(
        text.lines().count(),
        1 + 101,
        "the header and every step of 0.1 s at 1 ms"
    );
    assert!(
        others(&dir, "run.csv").is_empty(),
        "{:?}",
        others(&dir, "run.csv")
    );
}
