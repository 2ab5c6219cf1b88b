//! The MJCF element tree: every file parsed, `<include>`s replaced by the children of the
//! included file's `<mujoco>` element, each element and attribute remembering its file and line
//! and whether the loader used it (what is left unused is the conformance report).

use crate::error::{Error, Result};
use std::cell::Cell;
use std::path::{Path, PathBuf};

/// Elements nested deeper than this are refused (a body tree this deep is not a robot, and the
/// loader's recursion stays far from the stack's end).
pub(crate) const MAX_DEPTH: usize = 200;
/// At most this many `<include>`s are expanded (a file that includes another twice, which
/// includes another twice…, would otherwise grow exponentially).
const MAX_INCLUDES: usize = 1000;

/// One attribute of an element.
pub(crate) struct Attr {
    pub name: String,
    pub value: String,
    pub used: Cell<bool>,
}

/// One element, its attributes in file order and its children (includes expanded).
pub(crate) struct Element {
    pub tag: String,
    pub attrs: Vec<Attr>,
    pub children: Vec<Element>,
    /// Index into [`Tree::files`].
    pub file: usize,
    pub line: usize,
    pub used: Cell<bool>,
}

impl Element {
    /// The attribute `name`, marked as used.
    pub fn attr(&self, name: &str) -> Option<&str> {
        self.attrs.iter().find(|a| a.name == name).map(|a| {
            a.used.set(true);
            a.value.as_str()
        })
    }
    /// The child elements with tag `tag`.
    pub fn children_named<'a>(&'a self, tag: &'a str) -> impl Iterator<Item = &'a Element> + 'a {
        self.children.iter().filter(move |c| c.tag == tag)
    }
    /// Marks the element itself as used (its attributes are marked as they are read).
    pub fn take(&self) -> &Self {
        self.used.set(true);
        self
    }
}

/// Every file read (the main one first) and the root `<mujoco>` element.
pub(crate) struct Tree {
    pub files: Vec<String>,
    pub root: Element,
}

impl Tree {
    /// `file:line` of an element.
    pub fn at(&self, e: &Element) -> String {
        format!("{}:{}", self.files[e.file], e.line)
    }
    /// A parse error at an element: `file:line: message`.
    pub fn error(&self, e: &Element, message: impl Into<String>) -> Error {
        Error::parse_at(self.files[e.file].clone(), e.line, message)
    }
    /// A model error at an element: `file:line: message`.
    pub fn model_error(&self, e: &Element, message: impl std::fmt::Display) -> Error {
        Error::InvalidModel(format!("{}: {message}", self.at(e)))
    }
}

/// Parses the main file's text and every file it includes.
pub(crate) fn read(text: &str, file: &str) -> Result<Tree> {
    let mut r = Reader {
        files: vec![file.to_string()],
        stack: Vec::new(),
        includes: 0,
        main_dir: Path::new(file).parent().map(Path::to_path_buf),
    };
    let canonical = std::fs::canonicalize(file).unwrap_or_else(|_| PathBuf::from(file));
    r.stack.push(canonical);
    let root = r.parse_file(text, 0, 0)?;
    Ok(Tree {
        files: r.files,
        root,
    })
}

struct Reader {
    files: Vec<String>,
    /// The files being read, outermost first (a file on it that is included again is a cycle).
    stack: Vec<PathBuf>,
    includes: usize,
    main_dir: Option<PathBuf>,
}

impl Reader {
    fn parse_file(&mut self, text: &str, file: usize, depth: usize) -> Result<Element> {
        let name = self.files[file].clone();
        let doc = roxmltree::Document::parse(text).map_err(|e| {
            let p = e.pos();
            Error::Parse {
                file: name.clone(),
                line: Some(p.row as usize),
                column: Some(p.col as usize),
                message: format!("XML syntax error: {e}"),
            }
        })?;
        let line_starts: Vec<usize> = std::iter::once(0)
            .chain(text.match_indices('\n').map(|(k, _)| k + 1))
            .collect();
        let root = doc.root_element();
        let line = |n: roxmltree::Node| line_starts.partition_point(|&s| s <= n.range().start);
        if !root.has_tag_name("mujoco") {
            return Err(Error::parse_at(
                name,
                line(root),
                format!(
                    "the root element is <{}>, expected <mujoco>",
                    root.tag_name().name()
                ),
            ));
        }
        self.convert(root, file, &line, depth)
    }

    fn convert(
        &mut self,
        n: roxmltree::Node,
        file: usize,
        line: &dyn Fn(roxmltree::Node) -> usize,
        depth: usize,
    ) -> Result<Element> {
        if depth > MAX_DEPTH {
            return Err(Error::parse_at(
                self.files[file].clone(),
                line(n),
                format!("elements are nested more than {MAX_DEPTH} deep"),
            ));
        }
        let mut e = Element {
            tag: n.tag_name().name().to_string(),
            attrs: n
                .attributes()
                .map(|a| Attr {
                    name: a.name().to_string(),
                    value: a.value().to_string(),
                    used: Cell::new(false),
                })
                .collect(),
            children: Vec::new(),
            file,
            line: line(n),
            used: Cell::new(false),
        };
        for c in n.children().filter(|c| c.is_element()) {
            if c.has_tag_name("include") {
                let included = self.include(c, file, line(c), depth + 1)?;
                e.children.extend(included.children);
            } else {
                e.children.push(self.convert(c, file, line, depth + 1)?);
            }
        }
        Ok(e)
    }

    /// `<include file="…"/>`: the file relative to the including file's directory (or, as
    /// MuJoCo resolves it, to the main file's), its `<mujoco>` element's children.
    fn include(
        &mut self,
        n: roxmltree::Node,
        from: usize,
        at: usize,
        depth: usize,
    ) -> Result<Element> {
        let here = self.files[from].clone();
        let err = |m: String| Error::parse_at(here.clone(), at, m);
        let Some(name) = n.attribute("file") else {
            return Err(err("<include> has no 'file' attribute".into()));
        };
        self.includes += 1;
        if self.includes > MAX_INCLUDES {
            return Err(err(format!(
                "more than {MAX_INCLUDES} <include>s are expanded; the includes repeat too often"
            )));
        }
        let dir = Path::new(&here).parent().map(Path::to_path_buf);
        let candidates = [dir, self.main_dir.clone()];
        let path = candidates
            .iter()
            .map(|d| match d {
                Some(d) => d.join(name),
                None => PathBuf::from(name),
            })
            .find(|p| p.is_file())
            .ok_or_else(|| {
                err(format!(
                    "<include file=\"{name}\">: the file does not exist (looked beside {here})"
                ))
            })?;
        let canonical = std::fs::canonicalize(&path).unwrap_or_else(|_| path.clone());
        if let Some(k) = self.stack.iter().position(|p| *p == canonical) {
            let chain: Vec<String> = self.stack[k..]
                .iter()
                .chain(std::iter::once(&canonical))
                .map(|p| p.display().to_string())
                .collect();
            return Err(err(format!(
                "<include file=\"{name}\"> makes a cycle of includes: {}",
                chain.join(" → ")
            )));
        }
        let text = std::fs::read_to_string(&path)
            .map_err(|e| err(format!("<include file=\"{name}\">: {e}")))?;
        self.files.push(path.display().to_string());
        let index = self.files.len() - 1;
        self.stack.push(canonical);
        let element = self.parse_file(&text, index, depth)?;
        self.stack.pop();
        Ok(element)
    }
}
