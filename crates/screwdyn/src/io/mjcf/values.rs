//! Attribute values: lists of finite numbers, booleans and keywords, each error naming the
//! element that wrote the value (the element itself or the default class that set it).

use super::defaults::Styled;
use super::tree::{Element, Tree};
use crate::error::Result;
use nalgebra::Vector3;

/// Reads the attributes of one element (with its defaults) and reports errors at `file:line`.
#[derive(Clone, Copy)]
pub(crate) struct Values<'t> {
    pub tree: &'t Tree,
    pub styled: Styled<'t>,
}

impl<'t> Values<'t> {
    /// The element these values belong to.
    pub fn element(&self) -> &'t Element {
        self.styled.element
    }

    /// The raw text of attribute `name`.
    pub fn text(&self, name: &str) -> Option<&'t str> {
        self.styled.get(name).map(|(v, _)| v)
    }

    /// Attribute `name` as numbers: exactly `count` of them, or between `count` and `max`.
    pub fn numbers_between(
        &self,
        name: &str,
        count: usize,
        max: usize,
    ) -> Result<Option<Vec<f64>>> {
        let Some((s, at)) = self.styled.get(name) else {
            return Ok(None);
        };
        numbers(self.tree, at, name, s, count, max).map(Some)
    }

    /// Attribute `name` as exactly `count` numbers.
    pub fn numbers(&self, name: &str, count: usize) -> Result<Option<Vec<f64>>> {
        self.numbers_between(name, count, count)
    }

    /// Attribute `name` as one number.
    pub fn number(&self, name: &str) -> Result<Option<f64>> {
        Ok(self.numbers(name, 1)?.map(|v| v[0]))
    }

    /// Attribute `name` as one number that must not be negative.
    pub fn non_negative(&self, name: &str) -> Result<Option<f64>> {
        let x = self.number(name)?;
        if let Some(x) = x.filter(|x| *x < 0.0) {
            let (_, at) = self.styled.get(name).expect("just read");
            return Err(self.tree.error(
                at,
                format!(
                    "<{} {name}=\"{x}\"> is negative; it must be zero or more",
                    at.tag
                ),
            ));
        }
        Ok(x)
    }

    /// Attribute `name` as a 3-vector.
    pub fn vec3(&self, name: &str) -> Result<Option<Vector3<f64>>> {
        Ok(self
            .numbers(name, 3)?
            .map(|v| Vector3::new(v[0], v[1], v[2])))
    }

    /// Attribute `name` as one of `choices`.
    pub fn keyword(&self, name: &str, choices: &[&'static str]) -> Result<Option<&'static str>> {
        let Some((s, at)) = self.styled.get(name) else {
            return Ok(None);
        };
        choices
            .iter()
            .find(|c| **c == s.trim())
            .copied()
            .map(Some)
            .ok_or_else(|| {
                self.tree.error(
                    at,
                    format!(
                        "<{} {name}=\"{s}\"> is not one of {}",
                        at.tag,
                        choices.join(", ")
                    ),
                )
            })
    }

    /// Attribute `name` as `true`/`false`/`auto` (`None` when absent).
    pub fn tristate(&self, name: &str) -> Result<Option<&'static str>> {
        self.keyword(name, &["true", "false", "auto"])
    }

    /// A parse error at the element itself.
    pub fn error(&self, message: impl Into<String>) -> crate::Error {
        self.tree.error(self.element(), message)
    }
}

/// `s` as `count..=max` finite numbers, an error at `at` otherwise.
pub(crate) fn numbers(
    tree: &Tree,
    at: &Element,
    name: &str,
    s: &str,
    count: usize,
    max: usize,
) -> Result<Vec<f64>> {
    let mut v = Vec::with_capacity(max.min(16));
    for w in s.split_whitespace() {
        match w.parse::<f64>() {
            Ok(x) if x.is_finite() => v.push(x),
            _ => {
                return Err(tree.error(
                    at,
                    format!("<{} {name}=\"{s}\">: '{w}' is not a finite number", at.tag),
                ))
            }
        }
        if v.len() > max {
            break;
        }
    }
    if v.len() < count || v.len() > max {
        let expected = if count == max {
            format!("{count}")
        } else {
            format!("{count} to {max}")
        };
        return Err(tree.error(
            at,
            format!(
                "<{} {name}=\"{s}\"> has {} numbers, expected {expected}",
                at.tag,
                s.split_whitespace().count()
            ),
        ));
    }
    Ok(v)
}
