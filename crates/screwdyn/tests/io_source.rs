//! `io::load_source`: the model with the text it was parsed from and its path, read once; and
//! the typed errors of loading (an I/O error's kind and path, a parse error's file and line).

use screwdyn::io::{load_model, load_source, load_str, LoadOptions};
use screwdyn::Error;
use std::io::ErrorKind;
use std::path::{Path, PathBuf};

const DATA: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/");
const MODELS: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../../models/");

fn opts() -> LoadOptions {
    LoadOptions::default()
}

/// A fresh folder under the system's temporary directory.
fn scratch(tag: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("screwdyn-{tag}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

#[test]
fn a_file_comes_with_its_text_and_path_and_the_same_model_as_load_model() {
    for file in [
        "planar2.urdf",
        "planar2_dh.toml",
        "arm3_poe.toml",
        "arm3_native.toml",
    ] {
        let path = format!("{DATA}{file}");
        let loaded = load_source(&path, &opts()).unwrap();
        let on_disk = std::fs::read_to_string(&path).unwrap();
        assert_eq!(loaded.text.as_deref(), Some(on_disk.as_str()), "{file}");
        assert_eq!(loaded.path.as_deref(), Some(Path::new(&path)), "{file}");
        assert_eq!(loaded.model, load_model(&path).unwrap(), "{file}");
        // The text alone rebuilds the same model (what a front-end keeps to pickle it).
        assert_eq!(
            load_str(&on_disk, &path, &opts()).unwrap(),
            loaded.model,
            "{file}"
        );
    }
}

#[test]
fn a_builtin_comes_with_its_shipped_file_or_none_when_built_in_code() {
    for name in ["ur5", "panda", "branched"] {
        let loaded = load_source(&format!("builtin:{name}"), &opts()).unwrap();
        let shipped = std::fs::read_to_string(format!("{MODELS}{name}.toml")).unwrap();
        assert_eq!(loaded.text.as_deref(), Some(shipped.as_str()), "{name}");
        assert_eq!(loaded.path, None);
        assert_eq!(loaded.model, screwdyn::builtin::load(name).unwrap());
    }
    for name in ["planar2", "pendulum"] {
        let loaded = load_source(&format!("builtin:{name}"), &opts()).unwrap();
        assert_eq!((loaded.text, loaded.path), (None, None), "{name}");
        assert_eq!(loaded.model, screwdyn::builtin::load(name).unwrap());
    }
    let e = load_source("builtin:r2d2", &opts()).unwrap_err();
    assert!(matches!(e, Error::UnknownName { .. }), "{e:?}");
}

#[test]
fn io_errors_carry_the_kind_and_the_path() {
    let dir = scratch("io-kind");
    // A missing file: NotFound, as the operating system says.
    let missing = dir.join("missing.urdf");
    let e = load_source(missing.to_str().unwrap(), &opts()).unwrap_err();
    let Error::Io { path, kind, .. } = &e else {
        panic!("{e:?}")
    };
    assert_eq!(*kind, ErrorKind::NotFound);
    assert_eq!(path.as_deref(), Some(missing.as_path()));
    assert_eq!(e.io_kind(), Some(ErrorKind::NotFound));
    assert!(
        e.to_string().contains("missing.urdf: cannot be read"),
        "{e}"
    );
    // A folder named like a model: not a regular file.
    let folder = dir.join("folder.toml");
    std::fs::create_dir_all(&folder).unwrap();
    let e = load_source(folder.to_str().unwrap(), &opts()).unwrap_err();
    assert_eq!(e.io_kind(), Some(ErrorKind::InvalidInput), "{e:?}");
    assert!(e.to_string().contains("is not a regular file"), "{e}");
    // Not an I/O error: no kind.
    let e = load_source("robot.sdf", &opts()).unwrap_err();
    assert_eq!(e.io_kind(), None);
    std::fs::remove_dir_all(&dir).unwrap();
}

#[cfg(unix)]
#[test]
fn an_unreadable_file_is_permission_denied() {
    use std::os::unix::fs::PermissionsExt;
    let dir = scratch("io-perm");
    let file = dir.join("locked.toml");
    std::fs::write(&file, "format = \"dh\"\n").unwrap();
    std::fs::set_permissions(&file, std::fs::Permissions::from_mode(0o000)).unwrap();
    // Root reads any file: then there is nothing to check.
    if std::fs::read(&file).is_ok() {
        eprintln!("running as root, every file is readable; skipped");
    } else {
        let e = load_source(file.to_str().unwrap(), &opts()).unwrap_err();
        assert_eq!(e.io_kind(), Some(ErrorKind::PermissionDenied), "{e:?}");
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn parse_errors_carry_file_line_and_column() {
    // Line 3, column 5 of this text is where the TOML value is missing.
    let text = "format = \"dh\"\n[[row]]\na = \n";
    let e = load_str(text, "bad.toml", &opts()).unwrap_err();
    let Error::Parse {
        file, line, column, ..
    } = &e
    else {
        panic!("{e:?}")
    };
    assert_eq!(file, "bad.toml");
    assert_eq!(*line, Some(3));
    assert_eq!(*column, Some(5));
    assert!(e.to_string().starts_with("bad.toml:3:5: "), "{e}");
    // A DH row with a bad value: the row's line, no column.
    let text = "format = \"dh\"\n\n[[row]]\ntype = \"X\"\n";
    let e = load_str(text, "row.toml", &opts()).unwrap_err();
    assert!(
        matches!(
            &e,
            Error::Parse {
                line: Some(3),
                column: None,
                ..
            }
        ),
        "{e:?}"
    );
    assert!(e.to_string().starts_with("row.toml:3: DH row 1"), "{e}");
    // No line at all: the file alone.
    let e = load_str("name = \"x\"\n", "x.toml", &opts()).unwrap_err();
    assert!(matches!(&e, Error::Parse { line: None, .. }), "{e:?}");
    assert!(e.to_string().starts_with("x.toml: "), "{e}");
}
