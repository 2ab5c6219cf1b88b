//! The conformance report: every element and attribute of the file (includes expanded) that the
//! loader did not use, element by element, in file order.

use super::tree::{Element, Tree};

/// One element the MJCF loader ignored, entirely or in part.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Ignored {
    /// `file:line` of the element.
    pub location: String,
    /// The element's tag.
    pub element: String,
    /// Its `name` attribute, if any.
    pub name: Option<String>,
    /// The attributes ignored; empty when the whole element (and what it holds) is ignored.
    pub attributes: Vec<String>,
}

impl std::fmt::Display for Ignored {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}: <{}", self.location, self.element)?;
        if let Some(n) = &self.name {
            write!(f, " name=\"{n}\"")?;
        }
        if self.attributes.is_empty() {
            write!(f, "> ignored")
        } else {
            write!(f, ">: ignored {}", self.attributes.join(", "))
        }
    }
}

/// What the loader left unused: a whole element when it never looked at it (its children are
/// not listed again), else its unused attributes (`name` and `class` are never listed: they only
/// identify).
pub(crate) fn ignored(tree: &Tree) -> Vec<Ignored> {
    let mut out = Vec::new();
    visit(tree, &tree.root, &mut out);
    out
}

fn visit(tree: &Tree, e: &Element, out: &mut Vec<Ignored>) {
    let name = e
        .attrs
        .iter()
        .find(|a| a.name == "name")
        .map(|a| a.value.clone());
    if !e.used.get() {
        out.push(Ignored {
            location: tree.at(e),
            element: e.tag.clone(),
            name,
            attributes: Vec::new(),
        });
        return;
    }
    let attributes: Vec<String> = e
        .attrs
        .iter()
        .filter(|a| !a.used.get() && !matches!(a.name.as_str(), "name" | "class"))
        .map(|a| a.name.clone())
        .collect();
    if !attributes.is_empty() {
        out.push(Ignored {
            location: tree.at(e),
            element: e.tag.clone(),
            name,
            attributes,
        });
    }
    for c in &e.children {
        visit(tree, c, out);
    }
}
