//! `write_atomically` / `Page::save`: the page replaces an existing file whole, no temporary
//! file is left behind, and a folder that does not exist is a one-sentence `Io` error.

use screwdyn_view::{render_html, write_atomically, ViewOptions};

#[test]
fn pages_are_written_whole_and_failures_name_the_file() {
    let dir = std::env::temp_dir().join(format!("screwdyn-view-write-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("robot.html");
    std::fs::write(&path, "an older, longer page that must disappear entirely").unwrap();
    let page = render_html(&screwdyn::builtin::planar2(), &ViewOptions::default()).unwrap();
    page.save(&path).unwrap();
    assert_eq!(std::fs::read_to_string(&path).unwrap(), page.html);
    let left: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    assert_eq!(left, ["robot.html"], "no temporary file is left behind");

    let missing = dir.join("no-such-folder").join("robot.html");
    let e = write_atomically(&missing, b"x").unwrap_err();
    assert!(matches!(e, screwdyn::Error::Io { .. }), "{e:?}");
    let msg = e.to_string();
    assert!(
        msg.starts_with("cannot write ") && msg.contains("no-such-folder"),
        "{msg}"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}
