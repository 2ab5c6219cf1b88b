//! The arguments of `Model`'s methods that are not joint-space arrays: frames, links and joints
//! by name or index, external wrenches, reference frames and forward-dynamics methods.

use crate::convert::{fixed_states, ArrayIn};
use crate::errors::call_err;
use crate::model::PyModel;
use nalgebra::Vector6;
use pyo3::exceptions::{PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyString};
use screwdyn::dynamics::{ExternalWrenches, ForwardMethod};
use screwdyn::kinematics::Reference;

/// The external wrenches as the keyword arguments give them: `fext`, `fext_world` and
/// `tip_wrenches`.
pub(crate) type WrenchDicts<'a, 'py> = [Option<&'a Bound<'py, PyDict>>; 3];

impl PyModel {
    /// A frame given by name or index.
    pub(crate) fn frame(&self, f: &Bound<'_, PyAny>) -> PyResult<usize> {
        let n = self.model.frames().len();
        name_or_index(f, "frame", n, "frames", |name| self.model.frame_id(name))
    }

    /// A moving link (body) given by name or index.
    pub(crate) fn link(&self, b: &Bound<'_, PyAny>) -> PyResult<usize> {
        let n = self.model.nbodies();
        name_or_index(b, "link", n, "moving links", |name| {
            self.model.body_id(name)
        })
    }

    /// The frame of a link that may carry a wrench: by name any link, moving or attached by a
    /// fixed joint (`Model::link_frame_id`); by index a moving link, as [`Self::link`].
    pub(crate) fn link_frame(&self, b: &Bound<'_, PyAny>) -> PyResult<usize> {
        if let Ok(name) = b.cast::<PyString>() {
            return self.model.link_frame_id(&name.to_cow()?).map_err(call_err);
        }
        let body = self.link(b)?;
        self.model.body_frame(body).map_err(call_err)
    }

    /// A joint given by name or index.
    pub(crate) fn joint(&self, j: &Bound<'_, PyAny>) -> PyResult<usize> {
        let n = self.model.nq();
        name_or_index(j, "joint", n, "joints", |name| self.model.joint_id(name))
    }

    /// External wrenches from the keyword arguments `fext` (link → wrench on the link, in the
    /// link frame; a link attached by a fixed joint included), `fext_world` (link → wrench on the link, in the base frame) and
    /// `tip_wrenches` (frame → wrench the frame applies to the environment, in that frame).
    pub(crate) fn wrenches(
        &self,
        [fext, fext_world, tip_wrenches]: WrenchDicts<'_, '_>,
    ) -> PyResult<Option<ExternalWrenches>> {
        if fext.is_none() && fext_world.is_none() && tip_wrenches.is_none() {
            return Ok(None);
        }
        let mut ext = ExternalWrenches::new(&self.model);
        let wrench = |w: &Bound<'_, PyAny>, name: &'static str| -> PyResult<Vector6<f64>> {
            let arr: ArrayIn<'_> = w.extract()?;
            let s = fixed_states(&arr, name, 6, false)?;
            Ok(Vector6::from_column_slice(s.row(0)))
        };
        if let Some(d) = fext {
            for (k, w) in d.iter() {
                let f = self.link_frame(&k)?;
                ext.add_on_link(&self.model, f, wrench(&w, "a wrench of fext")?, false)
                    .map_err(call_err)?;
            }
        }
        if let Some(d) = fext_world {
            for (k, w) in d.iter() {
                let f = self.link_frame(&k)?;
                ext.add_on_link(&self.model, f, wrench(&w, "a wrench of fext_world")?, true)
                    .map_err(call_err)?;
            }
        }
        if let Some(d) = tip_wrenches {
            for (k, w) in d.iter() {
                let f = self.frame(&k)?;
                ext.add_tip(&self.model, f, wrench(&w, "a tip wrench")?)
                    .map_err(call_err)?;
            }
        }
        Ok(Some(ext))
    }
}

/// The frame a twist or Jacobian is written in: `world`, `local` or `world-aligned`
/// (Pinocchio's `WORLD`, `LOCAL`, `LOCAL_WORLD_ALIGNED` too: the library's spelling rule).
pub(crate) fn reference(s: &str) -> PyResult<Reference> {
    // The default as it is written, without the library's case folding (a `String` per call).
    if s == "world" {
        return Ok(Reference::World);
    }
    s.parse::<Reference>().map_err(call_err)
}

/// A forward-dynamics method: `aba`, `crba` or `walker-orin`.
pub(crate) fn method(s: &str) -> PyResult<ForwardMethod> {
    s.parse::<ForwardMethod>().map_err(call_err)
}

/// An item of the model given by its name (looked up by `by_name`) or by its index below `n`;
/// `kind` ("frame") and `plural` ("frames") word the messages.
fn name_or_index(
    x: &Bound<'_, PyAny>,
    kind: &str,
    n: usize,
    plural: &str,
    by_name: impl FnOnce(&str) -> screwdyn::Result<usize>,
) -> PyResult<usize> {
    // A type check first: a failed `extract` builds an exception object, which would cost an
    // index more than the lookup itself.
    if let Ok(name) = x.cast::<PyString>() {
        return by_name(&name.to_cow()?).map_err(call_err);
    }
    if let Ok(i) = x.extract::<i64>() {
        return usize::try_from(i).ok().filter(|&i| i < n).ok_or_else(|| {
            PyValueError::new_err(format!(
                "{kind} index {i} is out of range: the model has {n} {plural} (0…{})",
                n.saturating_sub(1)
            ))
        });
    }
    Err(PyTypeError::new_err(format!(
        "a {kind} is given by its name (str) or its index (int)"
    )))
}
