//! NumPy in, NumPy out: shape checks with clear messages, stacked states, output arrays, and
//! the Python classes results are wrapped in.

use numpy::{
    AllowTypeChange, BorrowError, PyArray1, PyArrayDyn, PyArrayLikeDyn, PyArrayMethods,
    PyReadwriteArrayDyn, PyUntypedArray, PyUntypedArrayMethods,
};
use pyo3::exceptions::{PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyFloat, PyInt, PyTuple};
use screwdyn::Model;
use std::borrow::Cow;

/// Anything NumPy can turn into a float64 array (arrays, lists, tuples, scalars).
pub type ArrayIn<'py> = PyArrayLikeDyn<'py, f64, AllowTypeChange>;

/// Joint vectors of at most this many values are copied onto the stack (`StateIn::Inline`).
pub const INLINE: usize = 16;

/// A joint-space argument (`q`, `v`, `a`, `tau`…) as the per-state methods take it. A float64,
/// aligned, contiguous vector — the one state of most calls — is copied at once under the GIL,
/// as rust-numpy's own `to_vec` reads it: onto the stack when it has at most [`INLINE`] values
/// (no allocation: a 6- or 7-joint state is 48–56 bytes; a small inline array because
/// arguments are moved by value through PyO3's extraction), into a `Vec` otherwise. That costs less
/// than registering and releasing a rust-numpy borrow of it (a hash-map entry per argument, a
/// fifth of a per-call `rnea` when measured). Anything else (stacked states, lists, other
/// dtypes, strided views) is converted as [`ArrayIn`] and borrowed for the call, a float64
/// `(N, nq)` array without a copy.
// The inline variant is large on purpose: boxing it would bring back the allocation it avoids.
#[allow(clippy::large_enum_variant)]
pub enum StateIn<'py> {
    Inline([f64; INLINE], [usize; 1]),
    Vector(Vec<f64>, [usize; 1]),
    Array(ArrayIn<'py>),
}

impl StateIn<'_> {
    /// The values of a single float64 vector taken as it came (`Inline` or `Vector`); `None`
    /// for an argument that went through conversion.
    #[inline]
    pub fn vector(&self) -> Option<&[f64]> {
        match self {
            StateIn::Inline(x, [n]) => Some(&x[..*n]),
            StateIn::Vector(x, _) => Some(x),
            StateIn::Array(_) => None,
        }
    }
}

impl<'py> FromPyObject<'_, 'py> for StateIn<'py> {
    type Error = PyErr;

    fn extract(ob: Borrowed<'_, 'py, PyAny>) -> PyResult<Self> {
        if let Ok(v) = ob.cast::<PyArray1<f64>>() {
            if v.data().is_aligned() {
                // SAFETY: the GIL is held for the whole copy and no Python code runs during it,
                // the read `PyArrayMethods::to_vec` makes; `as_slice` is `Err` unless the
                // vector is contiguous.
                if let Ok(x) = unsafe { v.as_slice() } {
                    let n = x.len();
                    if n <= INLINE {
                        let mut values = [0.0; INLINE];
                        values[..n].copy_from_slice(x);
                        return Ok(StateIn::Inline(values, [n]));
                    }
                    return Ok(StateIn::Vector(x.to_vec(), [n]));
                }
            }
        }
        Ok(StateIn::Array(ob.extract()?))
    }
}

/// The shape and row-major values of an array argument, whichever way it came in.
pub trait Values {
    fn shape(&self) -> &[usize];
    /// The values in row-major (C) order, borrowed where they already are.
    fn values(&self) -> Cow<'_, [f64]>;
}

impl Values for ArrayIn<'_> {
    fn shape(&self) -> &[usize] {
        let arr: &Bound<'_, PyArrayDyn<f64>> = self;
        arr.shape()
    }

    fn values(&self) -> Cow<'_, [f64]> {
        contiguous(self)
    }
}

impl Values for StateIn<'_> {
    fn shape(&self) -> &[usize] {
        match self {
            StateIn::Inline(_, shape) | StateIn::Vector(_, shape) => shape,
            StateIn::Array(a) => Values::shape(a),
        }
    }

    fn values(&self) -> Cow<'_, [f64]> {
        match self {
            StateIn::Inline(x, [n]) => Cow::Borrowed(&x[..*n]),
            StateIn::Vector(x, _) => Cow::Borrowed(x),
            StateIn::Array(a) => contiguous(a),
        }
    }
}

fn shape_text(shape: &[usize]) -> String {
    match shape {
        [] => "()".into(),
        [n] => format!("({n},)"),
        _ => format!(
            "({})",
            shape
                .iter()
                .map(|d| d.to_string())
                .collect::<Vec<_>>()
                .join(", ")
        ),
    }
}

/// One joint-space (or fixed-width) argument: a single vector or `N` stacked rows.
pub struct States<'a> {
    pub name: &'static str,
    pub data: Cow<'a, [f64]>,
    /// `Some(N)` for an `(N, width)` array.
    pub n: Option<usize>,
    pub width: usize,
}

impl States<'_> {
    /// No argument: a placeholder in an array of states being filled.
    pub const EMPTY: States<'static> = States {
        name: "",
        data: Cow::Borrowed(&[]),
        n: None,
        width: 0,
    };

    /// Row `k` (the single vector when not stacked).
    #[inline]
    pub fn row(&self, k: usize) -> &[f64] {
        match self.n {
            Some(_) => &self.data[k * self.width..(k + 1) * self.width],
            None => &self.data,
        }
    }

    /// The single vector; a stacked argument is refused with a sentence naming `func`.
    pub fn single(&self, func: &str) -> PyResult<&[f64]> {
        match self.n {
            None => Ok(&self.data),
            Some(n) => Err(PyValueError::new_err(format!(
                "{func} takes one state: {} has shape ({n}, {}), expected ({},)",
                self.name, self.width, self.width
            ))),
        }
    }
}

/// The values in row-major (C) order: borrowed when the array is C-contiguous, else copied in
/// logical order (`as_slice` alone would accept a Fortran-ordered array in memory order).
/// NumPy allows a float64 buffer that is not 8-byte aligned (a view into a byte buffer, an
/// array unpickled by Dask); a slice or view of it would be undefined behaviour, so it is read
/// element by element.
pub fn contiguous<'a>(arr: &'a ArrayIn<'_>) -> Cow<'a, [f64]> {
    if !arr.data().is_aligned() {
        return Cow::Owned(unaligned_values(arr));
    }
    match arr.as_slice() {
        Ok(s) if arr.is_c_contiguous() => Cow::Borrowed(s),
        _ => Cow::Owned(arr.as_array().iter().copied().collect()),
    }
}

/// The values of an unaligned array in logical order, by unaligned loads at its strides.
fn unaligned_values(arr: &ArrayIn<'_>) -> Vec<f64> {
    let (shape, strides) = (arr.shape(), arr.strides());
    let count: usize = shape.iter().product();
    let base = arr.data() as *const u8;
    let mut index = vec![0usize; shape.len()];
    let mut out = Vec::with_capacity(count);
    for _ in 0..count {
        let offset: isize = index
            .iter()
            .zip(strides)
            .map(|(&i, &s)| i as isize * s)
            .sum();
        // SAFETY: the array is borrowed read-only and `index` stays within `shape`, so the
        // element at `offset` bytes from the data pointer lies inside its buffer.
        out.push(unsafe { base.offset(offset).cast::<f64>().read_unaligned() });
        // The next index, the last axis fastest.
        for axis in (0..shape.len()).rev() {
            index[axis] += 1;
            if index[axis] < shape[axis] {
                break;
            }
            index[axis] = 0;
        }
    }
    out
}

/// A joint-space argument of `model`: shape `(nq,)` or `(N, nq)`. A wrong length is reported
/// with the library's sentence (`q has 3 values, the model has 6 joints: …`).
pub fn joint_states<'a>(
    model: &Model,
    arr: &'a impl Values,
    name: &'static str,
) -> PyResult<States<'a>> {
    let shape = arr.shape();
    let data = arr.values();
    let nq = model.nq();
    match shape.len() {
        1 => {
            model
                .check_vector(&data, name)
                .map_err(crate::errors::call_err)?;
            Ok(States {
                name,
                data,
                n: None,
                width: nq,
            })
        }
        2 => {
            if shape[1] != nq {
                let e = model
                    .check_vector(&data[..shape[1].min(data.len())], name)
                    .err()
                    .map(|e| e.to_string())
                    .unwrap_or_default();
                return Err(PyValueError::new_err(format!(
                    "{name} has shape {}, expected (N, {nq}) with one row per state: {e}",
                    shape_text(shape)
                )));
            }
            Ok(States {
                name,
                data,
                n: Some(shape[0]),
                width: nq,
            })
        }
        _ => Err(PyValueError::new_err(format!(
            "{name} has shape {}, expected ({nq},) for one state or (N, {nq}) for N stacked states",
            shape_text(shape)
        ))),
    }
}

/// A fixed-width argument (a wrench `(6,)`, a point `(3,)`), single or stacked `(N, width)`.
pub fn fixed_states<'a>(
    arr: &'a impl Values,
    name: &'static str,
    width: usize,
    stackable: bool,
) -> PyResult<States<'a>> {
    let shape = arr.shape();
    let data = arr.values();
    match shape {
        [w] if *w == width => Ok(States {
            name,
            data,
            n: None,
            width,
        }),
        [n, w] if *w == width && stackable => Ok(States {
            name,
            data,
            n: Some(*n),
            width,
        }),
        _ => Err(PyValueError::new_err(format!(
            "{name} has shape {}, expected ({width},){}",
            shape_text(shape),
            if stackable {
                format!(" or (N, {width})")
            } else {
                String::new()
            }
        ))),
    }
}

/// **The one broadcast rule for per-joint parameters** (limits, gains, damping, friction, a
/// trajectory's end points and boundary velocities, a constant torque): one value per joint, or
/// a single number (a Python or NumPy scalar, a 0-d array) that stands for the same value at all
/// `n` joints, as the CLI's `--vmax 1.5`. A vector is returned as given (its length is checked by
/// the caller or the library).
pub fn per_joint(a: &ArrayIn<'_>, name: &'static str, n: usize) -> PyResult<Vec<f64>> {
    if a.ndim() == 0 {
        return Ok(vec![contiguous(a)[0]; n]);
    }
    values_1d(a, name)
}

/// [`per_joint`] for `model`: a scalar gives `nq` copies; a vector must have `nq` finite values
/// (the library's sentence otherwise).
pub fn model_per_joint(model: &Model, a: &ArrayIn<'_>, name: &'static str) -> PyResult<Vec<f64>> {
    let v = per_joint(a, name, model.nq())?;
    model
        .check_vector(&v, name)
        .map_err(crate::errors::call_err)?;
    Ok(v)
}

/// The number of joints per-joint arguments without a model describe: the length of the first
/// vector among `args` (their end points), 1 when all are scalars.
pub fn joint_count(args: &[&ArrayIn<'_>]) -> usize {
    args.iter()
        .find(|a| a.ndim() >= 1)
        .map_or(1, |a| a.shape()[0])
}

/// A 1-D array argument (one value per joint: trajectory end points, limits, times) as a vector.
pub fn values_1d(a: &ArrayIn<'_>, name: &'static str) -> PyResult<Vec<f64>> {
    if a.ndim() != 1 {
        return Err(PyValueError::new_err(format!(
            "{name} must be a 1-D array (one value per joint), got {} dimensions",
            a.ndim()
        )));
    }
    Ok(contiguous(a).into_owned())
}

/// The rows of a 2-D array argument (its dimensions checked by the caller).
pub fn rows_of(a: &ArrayIn<'_>) -> Vec<Vec<f64>> {
    let width = a.shape().get(1).copied().unwrap_or(0).max(1);
    contiguous(a).chunks(width).map(<[f64]>::to_vec).collect()
}

/// The common number of states of stacked arguments (`None` when all are single).
pub fn batch_len(args: &[&States<'_>]) -> PyResult<Option<usize>> {
    let mut n: Option<(usize, &str)> = None;
    for a in args {
        if let Some(k) = a.n {
            match n {
                None => n = Some((k, a.name)),
                Some((m, other)) if m != k => {
                    return Err(PyValueError::new_err(format!(
                        "{} has {k} states but {other} has {m}: stacked arguments need the same number of rows",
                        a.name
                    )))
                }
                _ => {}
            }
        }
    }
    Ok(n.map(|(k, _)| k))
}

/// The `out=` argument of a call whose result has `shape`, borrowed for writing: a float64,
/// C-contiguous, writeable NumPy array of exactly that shape that shares no memory with the
/// call's array inputs. Anything else is refused with a sentence saying what was expected
/// (`TypeError` for a non-array or another dtype, `ValueError` for the rest).
pub fn out_array<'py>(
    out: &Bound<'py, PyAny>,
    shape: &[usize],
) -> PyResult<PyReadwriteArrayDyn<'py, f64>> {
    let expected = shape_text(shape);
    let Ok(untyped) = out.cast::<PyUntypedArray>() else {
        return Err(PyTypeError::new_err(format!(
            "out must be a NumPy float64 array of shape {expected}, got {}",
            out.get_type().name()?
        )));
    };
    let Ok(arr) = out.cast::<PyArrayDyn<f64>>() else {
        return Err(PyTypeError::new_err(format!(
            "out has dtype {}, expected float64 (shape {expected})",
            untyped.dtype()
        )));
    };
    if arr.shape() != shape {
        return Err(PyValueError::new_err(format!(
            "out has shape {}, expected {expected}",
            shape_text(arr.shape())
        )));
    }
    if !arr.is_c_contiguous() {
        return Err(PyValueError::new_err(
            "out must be C-contiguous (a fresh np.empty array or a contiguous slice of rows)",
        ));
    }
    arr.try_readwrite().map_err(|e| {
        PyValueError::new_err(match e {
            BorrowError::NotWriteable => "out is read-only".to_string(),
            _ => "out shares memory with an input argument; pass a separate array".to_string(),
        })
    })
}

/// A float64 NumPy array of `shape` that takes ownership of `data` (no copy).
pub fn array<'py>(py: Python<'py>, data: Vec<f64>, shape: &[usize]) -> PyResult<Bound<'py, PyAny>> {
    let flat = numpy::PyArray1::from_vec(py, data);
    Ok(flat.reshape(shape.to_vec())?.into_any())
}

/// `rows` as an `(len, width)` array.
pub fn rows_array<'py>(
    py: Python<'py>,
    rows: &[Vec<f64>],
    width: usize,
) -> PyResult<Bound<'py, PyAny>> {
    let mut flat = Vec::with_capacity(rows.len() * width);
    for r in rows {
        flat.extend_from_slice(r);
    }
    array(py, flat, &[rows.len(), width])
}

/// A dense matrix as a row-major array.
pub fn matrix<'py>(py: Python<'py>, m: &nalgebra::DMatrix<f64>) -> PyResult<Bound<'py, PyAny>> {
    array(
        py,
        m.transpose().as_slice().to_vec(),
        &[m.nrows(), m.ncols()],
    )
}

/// A read-only array: model properties are copies, so writing into one would silently change
/// nothing; NumPy refuses the write instead ("assignment destination is read-only").
pub fn frozen<'py>(a: Bound<'py, PyAny>) -> PyResult<Bound<'py, PyAny>> {
    let kw = pyo3::types::PyDict::new(a.py());
    kw.set_item("write", false)?;
    a.call_method("setflags", (), Some(&kw))?;
    Ok(a)
}

/// A vector as a 1-D array.
pub fn vector<'py>(py: Python<'py>, v: &[f64]) -> PyResult<Bound<'py, PyAny>> {
    array(py, v.to_vec(), &[v.len()])
}

/// Whether every value is finite, in one pass the compiler vectorises (no chain of dependent
/// adds, no early exit): the common case of the library's result check, which is called only
/// when this fails, to word the error.
#[inline]
pub fn all_finite(values: &[f64]) -> bool {
    values.iter().fold(true, |finite, x| finite & x.is_finite())
}

/// Writes `m` row-major into `out`.
#[inline]
pub fn write_rows<R: nalgebra::Dim, C: nalgebra::Dim, S: nalgebra::RawStorage<f64, R, C>>(
    m: &nalgebra::Matrix<f64, R, C, S>,
    out: &mut [f64],
) {
    // Row by row, no division or bounds check per entry (a mass matrix is 36–81 of them per
    // call; measured with callgrind against indexing and against strided iterators).
    let (rows, cols) = m.shape();
    for (i, row) in out.chunks_exact_mut(cols.max(1)).take(rows).enumerate() {
        for (j, o) in row.iter_mut().enumerate() {
            // SAFETY: i < rows (`take`) and j < cols (the row's length).
            *o = unsafe { *m.get_unchecked((i, j)) };
        }
    }
}

/// A `(4, 4)` homogeneous matrix of a pose, row-major.
#[inline]
pub fn write_pose(h: &screwdyn::spatial::Se3, out: &mut [f64]) {
    write_rows(&h.to_matrix(), out);
}

/// The Python class `module.class`: the result classes of `screwdyn._results` (`ClosedForm`,
/// `SimResult`…) and `screwdyn._view.View`, which wrap the arrays a method returns for
/// notebooks, pandas and matplotlib.
pub fn python_class<'py>(
    py: Python<'py>,
    module: &str,
    class: &str,
) -> PyResult<Bound<'py, PyAny>> {
    py.import(module)?.getattr(class)
}

/// Python's `float(x)`, for the number arguments the Python layer converted so before these
/// methods were native (`simulate`'s `duration`, `dt`, tolerances; `torque_profile`'s `dt`).
pub fn as_float(x: &Bound<'_, PyAny>) -> PyResult<f64> {
    match x.cast::<PyFloat>() {
        Ok(f) => Ok(f.value()),
        Err(_) => x.py().get_type::<PyFloat>().call1((x,))?.extract(),
    }
}

/// Python's `int(x)`, for the counts and seeds the Python layer converted so (`record_every`,
/// `states`, `seed`, the view's caps).
pub fn as_int<'py, T>(x: &Bound<'py, PyAny>) -> PyResult<T>
where
    T: for<'a> FromPyObject<'a, 'py, Error = PyErr>,
{
    x.py().get_type::<PyInt>().call1((x,))?.extract()
}

/// Python's `bool(x)`, for the `friction` flags the Python layer converted so.
pub fn truthy(x: &Bound<'_, PyAny>) -> PyResult<bool> {
    x.is_truthy()
}

/// `()`, the default of a sequence argument (`simulate`'s `disturbances` and `frames`,
/// `view`'s `package_path`).
pub fn empty_tuple() -> Py<PyAny> {
    Python::attach(|py| PyTuple::empty(py).into_any().unbind())
}
