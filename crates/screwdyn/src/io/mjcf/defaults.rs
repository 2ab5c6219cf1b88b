//! `<default>` classes and MuJoCo's precedence: an attribute written on the element wins; else
//! the element's `class`, else the `childclass` of the nearest enclosing body (or frame) that
//! has one, else the top-level class `main`; a class that does not set the attribute passes the
//! question to the class it is nested in, up to `main`; what no class sets is MuJoCo's default.

use super::tree::{Element, Tree};
use crate::error::Result;
use std::collections::HashMap;

/// The actuator shortcuts: in a default class they all set the one actuator default.
const ACTUATOR_TAGS: [&str; 10] = [
    "general",
    "motor",
    "position",
    "velocity",
    "intvelocity",
    "damper",
    "cylinder",
    "muscle",
    "adhesion",
    "plugin",
];

/// The key under which a default element (or an element looking up its defaults) is filed.
pub(crate) fn default_key(tag: &str) -> &str {
    if ACTUATOR_TAGS.contains(&tag) {
        "actuator"
    } else {
        tag
    }
}

struct Class<'t> {
    parent: Option<usize>,
    /// The class's own default elements by key, in file order.
    own: HashMap<&'t str, Vec<&'t Element>>,
}

/// Every default class, found by name.
pub(crate) struct Defaults<'t> {
    classes: Vec<Class<'t>>,
    by_name: HashMap<&'t str, usize>,
}

/// The class an element reads its defaults from.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct ClassId(usize);

impl<'t> Defaults<'t> {
    /// Reads every `<default>` element under the root (nested ones inherit from the enclosing).
    pub fn read(tree: &'t Tree) -> Result<Self> {
        let mut d = Defaults {
            classes: vec![Class {
                parent: None,
                own: HashMap::new(),
            }],
            by_name: HashMap::new(),
        };
        d.by_name.insert("main", 0);
        for top in tree.root.children_named("default") {
            top.take();
            // The top-level <default> is `main` whatever it is called.
            top.attr("class");
            d.fill(tree, top, 0)?;
        }
        Ok(d)
    }

    fn fill(&mut self, tree: &'t Tree, e: &'t Element, class: usize) -> Result<()> {
        for c in &e.children {
            if c.tag == "default" {
                c.take();
                let Some(name) = c.attr("class") else {
                    return Err(tree.error(c, "a nested <default> has no 'class' attribute"));
                };
                if self.by_name.contains_key(name) {
                    return Err(tree.error(c, format!("default class '{name}' is defined twice")));
                }
                self.classes.push(Class {
                    parent: Some(class),
                    own: HashMap::new(),
                });
                let k = self.classes.len() - 1;
                self.by_name.insert(name, k);
                self.fill(tree, c, k)?;
            } else {
                self.classes[class]
                    .own
                    .entry(default_key(&c.tag))
                    .or_default()
                    .push(c);
            }
        }
        Ok(())
    }

    /// The class `main`.
    pub fn main(&self) -> ClassId {
        ClassId(0)
    }

    /// The class named `name`; an unknown name is an error at `at`.
    pub fn class(&self, tree: &Tree, at: &Element, name: &str) -> Result<ClassId> {
        self.by_name.get(name).map(|&k| ClassId(k)).ok_or_else(|| {
            tree.error(
                at,
                format!(
                    "<{}> names default class '{name}', which is not defined",
                    at.tag
                ),
            )
        })
    }

    /// The class of element `e`: its own `class`, else `inherited` (the enclosing childclass or
    /// `main`).
    pub fn class_of(&self, tree: &Tree, e: &Element, inherited: ClassId) -> Result<ClassId> {
        match e.attr("class") {
            Some(name) => self.class(tree, e, name),
            None => Ok(inherited),
        }
    }

    /// The default of attribute `name` for elements of tag `tag` in class `class`, with the
    /// default element that sets it (the class, then the classes it is nested in).
    pub fn lookup(&self, class: ClassId, tag: &str, name: &str) -> Option<(&'t str, &'t Element)> {
        let key = default_key(tag);
        let mut k = Some(class.0);
        while let Some(c) = k {
            let class = &self.classes[c];
            if let Some(list) = class.own.get(key) {
                for e in list.iter().rev() {
                    if let Some(v) = e.attr(name) {
                        e.take();
                        return Some((v, e));
                    }
                }
            }
            k = class.parent;
        }
        None
    }
}

/// An element with its class: attributes read from the element, else from the class chain.
#[derive(Clone, Copy)]
pub(crate) struct Styled<'t> {
    pub element: &'t Element,
    pub class: ClassId,
    pub defaults: &'t Defaults<'t>,
}

impl<'t> Styled<'t> {
    /// The attribute `name` and the element it was written on (the element or a default).
    pub fn get(&self, name: &str) -> Option<(&'t str, &'t Element)> {
        match self.element.attr(name) {
            Some(v) => Some((v, self.element)),
            None => self.defaults.lookup(self.class, &self.element.tag, name),
        }
    }
}
