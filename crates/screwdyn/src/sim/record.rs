//! [`Recording`]: what a simulation or torque profile produced, sample by sample, with CSV and
//! JSON output (column names `t`, `q.<joint>`, …, listed in docs/cli.md).

use super::limit_events::LimitEvent;
use crate::error::{Error, Result};
use crate::format::{csv_field, NumberText};
use crate::spatial::Se3;
use std::io::Write;

/// One recorded sample of a run, borrowed from the simulator: what a [`SampleSink`] receives.
#[derive(Clone, Copy, Debug)]
pub struct Sample<'a> {
    /// Time (s).
    pub t: f64,
    /// Joint positions.
    pub q: &'a [f64],
    /// Joint velocities.
    pub v: &'a [f64],
    /// Joint accelerations.
    pub a: &'a [f64],
    /// Applied joint torques (after the joint effects).
    pub tau: &'a [f64],
    /// Kinetic energy `½ q̇ᵀ M q̇` (J).
    pub kinetic_energy: f64,
    /// Potential energy in gravity, plus the joint springs' `½ k (q − q_spring)²` in a
    /// simulation where they act (J).
    pub potential_energy: f64,
    /// Poses `H_f^0` of the recorded frames.
    pub poses: &'a [Se3],
}

impl Sample<'_> {
    /// Appends the sample's values to `row` in the order of [`sample_columns`].
    pub fn write_values(&self, row: &mut Vec<f64>) {
        row.push(self.t);
        for x in [self.q, self.v, self.a, self.tau] {
            row.extend_from_slice(x);
        }
        row.extend([
            self.kinetic_energy,
            self.potential_energy,
            self.kinetic_energy + self.potential_energy,
        ]);
        for h in self.poses {
            row.extend(h.translation.iter());
        }
    }
}

/// Where a simulation sends its samples as they are recorded ([`simulate_into`](super::simulate_into)):
/// a [`Recording`] in memory, or a writer that streams them to a file.
pub trait SampleSink {
    /// Called once before the first sample with the joint and recorded frame names.
    ///
    /// # Errors
    /// Whatever the sink cannot do (e.g. write a header).
    fn begin(&mut self, joints: &[String], frames: &[String]) -> Result<()>;
    /// Receives one sample.
    ///
    /// # Errors
    /// Whatever the sink cannot do (e.g. write a row); the simulation stops with it.
    fn push(&mut self, sample: &Sample) -> Result<()>;
    /// Receives an event at a joint's position limit (a start outside the limits, a contact
    /// with a limit stop), before the sample at or after its time; ignored unless the sink
    /// keeps events.
    ///
    /// # Errors
    /// Whatever the sink cannot do; the simulation stops with it.
    fn event(&mut self, _event: &LimitEvent) -> Result<()> {
        Ok(())
    }
}

/// Column names of a run: `t`, `q.<joint>`…, `v.<joint>`…, `a.<joint>`…, `tau.<joint>`…,
/// `kinetic_energy`, `potential_energy`, `total_energy`, then `pose.<frame>.x|y|z` per frame.
///
/// ```
/// let c = screwdyn::sim::sample_columns(&["j1".into()], &["tool".into()]);
/// assert_eq!(c.join(","), "t,q.j1,v.j1,a.j1,tau.j1,kinetic_energy,potential_energy,total_energy,pose.tool.x,pose.tool.y,pose.tool.z");
/// ```
pub fn sample_columns(joints: &[String], frames: &[String]) -> Vec<String> {
    let mut c = vec!["t".to_string()];
    for key in ["q", "v", "a", "tau"] {
        c.extend(joints.iter().map(|j| format!("{key}.{j}")));
    }
    c.extend(["kinetic_energy", "potential_energy", "total_energy"].map(String::from));
    for f in frames {
        c.extend(["x", "y", "z"].map(|k| format!("pose.{f}.{k}")));
    }
    c
}

/// Time series of a run: `t`, `q`, `q̇`, `q̈`, `τ`, energies and chosen frame poses.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Recording {
    /// Joint names (the column suffixes).
    pub joints: Vec<String>,
    /// Sample times (s).
    pub t: Vec<f64>,
    /// Positions, one vector per sample.
    pub q: Vec<Vec<f64>>,
    /// Velocities.
    pub v: Vec<Vec<f64>>,
    /// Accelerations.
    pub a: Vec<Vec<f64>>,
    /// Applied joint torques (after saturation, damping, friction and limits).
    pub tau: Vec<Vec<f64>>,
    /// Kinetic energy `½ q̇ᵀ M q̇` (J).
    pub kinetic_energy: Vec<f64>,
    /// Potential energy in gravity, plus the joint springs' `½ k (q − q_spring)²` in a
    /// simulation where they act (J).
    pub potential_energy: Vec<f64>,
    /// Their sum (J).
    pub total_energy: Vec<f64>,
    /// Names of the recorded frames.
    pub frames: Vec<String>,
    /// Poses of the recorded frames, one vector (in `frames` order) per sample.
    pub poses: Vec<Vec<Se3>>,
    /// What happened at the joints' position limits: a start outside them, each contact with
    /// a limit stop (in time order).
    pub events: Vec<LimitEvent>,
}

impl Recording {
    /// An empty recording for these joints and frames.
    pub fn new(joints: Vec<String>, frames: Vec<String>) -> Self {
        Recording {
            joints,
            frames,
            ..Default::default()
        }
    }

    /// Makes room for `samples` more samples, or refuses up front with the memory they would
    /// need, so that a recording too large for the machine is an error and not an allocation
    /// failure part-way (which aborts the process).
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] naming the samples and the gigabytes they need.
    ///
    /// ```
    /// let mut r = screwdyn::sim::Recording::new(vec!["j1".into()], vec![]);
    /// r.reserve(1000).unwrap();
    /// let e = r.reserve(1 << 50).unwrap_err().to_string();
    /// assert!(e.contains("GB of memory"), "{e}");
    /// ```
    pub fn reserve(&mut self, samples: usize) -> Result<()> {
        // Per sample: t and three energies, four joint vectors (their headers and values, with
        // the allocator's overhead) and the frame poses.
        let vector = 3 * 8 + 16 + 8 * self.joints.len();
        let per_sample = 4 * 8 + 4 * vector + 24 + 16 + self.frames.len() * 96;
        let bytes = (samples as f64) * (per_sample as f64);
        let refuse = || {
            Error::InvalidArgument(format!(
                "holding {samples} samples needs about {:.1} GB of memory, more than can be allocated; use a larger step or a shorter motion",
                bytes / 1e9
            ))
        };
        // Probe the whole amount once (nothing is touched, so nothing is committed), then
        // reserve the per-sample vectors.
        let total = usize::try_from(bytes as u128).map_err(|_| refuse())?;
        Vec::<u8>::new()
            .try_reserve_exact(total)
            .map_err(|_| refuse())?;
        for x in [
            &mut self.t,
            &mut self.kinetic_energy,
            &mut self.potential_energy,
            &mut self.total_energy,
        ] {
            x.try_reserve_exact(samples).map_err(|_| refuse())?;
        }
        for x in [&mut self.q, &mut self.v, &mut self.a, &mut self.tau] {
            x.try_reserve_exact(samples).map_err(|_| refuse())?;
        }
        Ok(())
    }

    /// Number of samples.
    pub fn len(&self) -> usize {
        self.t.len()
    }

    /// Whether there is no sample.
    pub fn is_empty(&self) -> bool {
        self.t.is_empty()
    }

    /// Column names: see [`sample_columns`].
    pub fn columns(&self) -> Vec<String> {
        sample_columns(&self.joints, &self.frames)
    }

    /// Writes one CSV row per sample under [`Recording::columns`] (see [`CsvSampleWriter`]).
    ///
    /// # Errors
    /// [`Error::Io`] when writing fails.
    ///
    /// ```
    /// let mut r = screwdyn::sim::Recording::new(vec!["j1".into()], vec![]);
    /// use screwdyn::sim::{Sample, SampleSink};
    /// r.push(&Sample { t: 0.5, q: &[1.0], v: &[2.0], a: &[3.0], tau: &[4.0],
    ///                  kinetic_energy: 1.0, potential_energy: 2.0, poses: &[] }).unwrap();
    /// let mut out = Vec::new();
    /// r.write_csv(&mut out).unwrap();
    /// let text = String::from_utf8(out).unwrap();
    /// assert_eq!(text.lines().next().unwrap(), "t,q.j1,v.j1,a.j1,tau.j1,kinetic_energy,potential_energy,total_energy");
    /// assert_eq!(text.lines().nth(1).unwrap(), "0.5,1.0,2.0,3.0,4.0,1.0,2.0,3.0");
    /// ```
    pub fn write_csv(&self, w: &mut impl Write) -> Result<()> {
        let mut out = CsvSampleWriter::new(w);
        out.begin(&self.joints, &self.frames)?;
        for k in 0..self.len() {
            out.push(&self.sample(k)?)?;
        }
        out.flush()
    }

    /// Sample `k`, borrowed.
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] when there is no sample `k`.
    pub fn sample(&self, k: usize) -> Result<Sample<'_>> {
        if k >= self.len() {
            return Err(Error::InvalidArgument(format!(
                "sample {k} is out of range: the recording has {} samples",
                self.len()
            )));
        }
        Ok(Sample {
            t: self.t[k],
            q: &self.q[k],
            v: &self.v[k],
            a: &self.a[k],
            tau: &self.tau[k],
            kinetic_energy: self.kinetic_energy[k],
            potential_energy: self.potential_energy[k],
            poses: self.poses.get(k).map_or(&[], |p| p.as_slice()),
        })
    }

    /// The recording as JSON: the same names as the CSV columns, each holding an array over
    /// samples (`q.<joint>` etc.), plus `joints`, `t`, per frame `poses.<frame>` as 4×4
    /// row-major matrices, and `events` (see [`LimitEvent::to_json`]).
    pub fn to_json(&self) -> serde_json::Value {
        let mut m = serde_json::Map::new();
        m.insert("joints".into(), self.joints.clone().into());
        m.insert("t".into(), self.t.clone().into());
        for (key, x) in [
            ("q", &self.q),
            ("v", &self.v),
            ("a", &self.a),
            ("tau", &self.tau),
        ] {
            for (i, j) in self.joints.iter().enumerate() {
                let col: Vec<f64> = x.iter().map(|r| r[i]).collect();
                m.insert(format!("{key}.{j}"), col.into());
            }
        }
        m.insert("kinetic_energy".into(), self.kinetic_energy.clone().into());
        m.insert(
            "potential_energy".into(),
            self.potential_energy.clone().into(),
        );
        m.insert("total_energy".into(), self.total_energy.clone().into());
        for (fi, f) in self.frames.iter().enumerate() {
            let series: Vec<serde_json::Value> = self
                .poses
                .iter()
                .map(|p| {
                    let h = p[fi].to_matrix();
                    (0..4)
                        .map(|r| (0..4).map(|c| h[(r, c)]).collect::<Vec<_>>())
                        .collect::<Vec<_>>()
                        .into()
                })
                .collect();
            m.insert(format!("poses.{f}"), series.into());
        }
        let events = self.events.iter().map(LimitEvent::to_json).collect();
        m.insert("events".into(), serde_json::Value::Array(events));
        serde_json::Value::Object(m)
    }
}

impl SampleSink for Recording {
    fn begin(&mut self, joints: &[String], frames: &[String]) -> Result<()> {
        self.joints = joints.to_vec();
        self.frames = frames.to_vec();
        Ok(())
    }

    /// Appends one sample; `Err(InvalidArgument)` when its vectors do not have one entry per
    /// joint (or per recorded frame).
    fn push(&mut self, s: &Sample) -> Result<()> {
        let n = self.joints.len();
        let lens = [s.q.len(), s.v.len(), s.a.len(), s.tau.len()];
        if lens.iter().any(|&l| l != n) || s.poses.len() != self.frames.len() {
            return Err(Error::InvalidArgument(format!(
                "a sample with q, q̇, q̈, τ of {lens:?} values and {} poses does not fit a recording of {n} joints and {} frames",
                s.poses.len(),
                self.frames.len()
            )));
        }
        self.t.push(s.t);
        self.q.push(s.q.to_vec());
        self.v.push(s.v.to_vec());
        self.a.push(s.a.to_vec());
        self.tau.push(s.tau.to_vec());
        self.kinetic_energy.push(s.kinetic_energy);
        self.potential_energy.push(s.potential_energy);
        self.total_energy
            .push(s.kinetic_energy + s.potential_energy);
        if !self.frames.is_empty() {
            self.poses.push(s.poses.to_vec());
        }
        Ok(())
    }

    fn event(&mut self, event: &LimitEvent) -> Result<()> {
        self.events.push(event.clone());
        Ok(())
    }
}

/// A [`SampleSink`] that writes each sample as a CSV row as soon as it arrives (header from
/// [`sample_columns`], names quoted where CSV needs it, numbers in shortest round-trip form).
///
/// ```
/// use screwdyn::sim::{CsvSampleWriter, Sample, SampleSink};
/// let mut w = CsvSampleWriter::new(Vec::new());
/// w.begin(&["j,1".into()], &[]).unwrap();
/// w.push(&Sample { t: 0.0, q: &[1.0], v: &[0.5], a: &[0.0], tau: &[2.0],
///                  kinetic_energy: 0.25, potential_energy: 1.0, poses: &[] }).unwrap();
/// let text = String::from_utf8(w.into_inner()).unwrap();
/// assert_eq!(text, "t,\"q.j,1\",\"v.j,1\",\"a.j,1\",\"tau.j,1\",kinetic_energy,potential_energy,total_energy\n0.0,1.0,0.5,0.0,2.0,0.25,1.0,1.25\n");
/// ```
pub struct CsvSampleWriter<W: Write> {
    out: W,
    row: Vec<f64>,
    line: String,
    number: NumberText,
}

impl<W: Write> CsvSampleWriter<W> {
    /// Streams to `out` (wrap a file in a `BufWriter`).
    pub fn new(out: W) -> Self {
        CsvSampleWriter {
            out,
            row: Vec::new(),
            line: String::new(),
            number: NumberText::new(),
        }
    }
    /// The writer, once the run is over.
    pub fn into_inner(self) -> W {
        self.out
    }
    /// Flushes the underlying writer.
    ///
    /// # Errors
    /// [`Error::Io`] when the writer fails.
    pub fn flush(&mut self) -> Result<()> {
        self.out.flush().map_err(io_error)
    }
}

fn io_error(e: std::io::Error) -> Error {
    Error::io(None, e.kind(), format!("writing the run failed ({e})"))
}

/// A JSON serialisation failure while writing a run (kind `Other`).
fn json_error(e: serde_json::Error) -> Error {
    Error::io(None, std::io::ErrorKind::Other, e.to_string())
}

impl<W: Write> SampleSink for CsvSampleWriter<W> {
    fn begin(&mut self, joints: &[String], frames: &[String]) -> Result<()> {
        let header: Vec<String> = sample_columns(joints, frames)
            .iter()
            .map(|c| csv_field(c).into_owned())
            .collect();
        writeln!(self.out, "{}", header.join(",")).map_err(io_error)
    }

    fn push(&mut self, s: &Sample) -> Result<()> {
        self.row.clear();
        s.write_values(&mut self.row);
        self.line.clear();
        for (k, x) in self.row.iter().enumerate() {
            if k > 0 {
                self.line.push(',');
            }
            self.line.push_str(self.number.csv(*x));
        }
        self.line.push('\n');
        self.out.write_all(self.line.as_bytes()).map_err(io_error)
    }
}

/// A [`SampleSink`] that writes the run as the JSON object of [`Recording::to_json`] (one array
/// per column) without holding it in memory: each column is spooled to a temporary file as the
/// samples arrive and the object is assembled by [`finish`](JsonSampleWriter::finish).
///
/// ```
/// use screwdyn::sim::{JsonSampleWriter, Sample, SampleSink};
/// let mut w = JsonSampleWriter::new(Vec::new());
/// w.begin(&["j1".into()], &[]).unwrap();
/// for t in [0.0, 0.5] {
///     w.push(&Sample { t, q: &[1.0], v: &[0.0], a: &[0.0], tau: &[2.0],
///                      kinetic_energy: 0.0, potential_energy: 1.0, poses: &[] }).unwrap();
/// }
/// let json: serde_json::Value = serde_json::from_slice(&w.finish().unwrap()).unwrap();
/// assert_eq!(json["t"], serde_json::json!([0.0, 0.5]));
/// assert_eq!(json["tau.j1"], serde_json::json!([2.0, 2.0]));
/// ```
pub struct JsonSampleWriter<W: Write> {
    out: W,
    joints: Vec<String>,
    /// Column name and its spool of comma-separated JSON values, in output order.
    columns: Vec<(String, std::io::BufWriter<std::fs::File>)>,
    samples: usize,
    row: Vec<f64>,
    number: NumberText,
    /// The events so far, as JSON text each.
    events: Vec<String>,
}

impl<W: Write> JsonSampleWriter<W> {
    /// Will write the object to `out` when finished.
    pub fn new(out: W) -> Self {
        JsonSampleWriter {
            out,
            joints: Vec::new(),
            columns: Vec::new(),
            samples: 0,
            row: Vec::new(),
            number: NumberText::new(),
            events: Vec::new(),
        }
    }

    /// Writes the JSON object and returns the writer.
    ///
    /// # Errors
    /// [`Error::Io`] when a spool cannot be read back or the writer fails.
    pub fn finish(mut self) -> Result<W> {
        use std::io::{BufRead, Seek};
        let names = serde_json::to_string(&self.joints).map_err(json_error)?;
        write!(self.out, "{{\"joints\":{names}").map_err(io_error)?;
        for (name, spool) in self.columns {
            let key = serde_json::to_string(&name).map_err(json_error)?;
            write!(self.out, ",{key}:[").map_err(io_error)?;
            let mut file = spool.into_inner().map_err(|e| io_error(e.into_error()))?;
            file.rewind().map_err(io_error)?;
            // Copied through the reader's own (heap) buffer: a 64 KB array on the stack would
            // be touched page by page on entry, in every run that finishes a writer.
            let mut reader = std::io::BufReader::with_capacity(1 << 16, file);
            let mut first = true;
            loop {
                let buf = reader.fill_buf().map_err(io_error)?;
                let k = buf.len();
                if k == 0 {
                    break;
                }
                // Every value is spooled preceded by a comma; the very first one is dropped:
                // the spool starts with ",".
                let chunk = if first { &buf[1..] } else { buf };
                first = false;
                self.out.write_all(chunk).map_err(io_error)?;
                reader.consume(k);
            }
            self.out.write_all(b"]").map_err(io_error)?;
        }
        writeln!(self.out, ",\"events\":[{}]}}", self.events.join(",")).map_err(io_error)?;
        self.out.flush().map_err(io_error)?;
        Ok(self.out)
    }
}

impl<W: Write> SampleSink for JsonSampleWriter<W> {
    fn begin(&mut self, joints: &[String], frames: &[String]) -> Result<()> {
        self.joints = joints.to_vec();
        let mut names = vec!["t".to_string()];
        for key in ["q", "v", "a", "tau"] {
            names.extend(joints.iter().map(|j| format!("{key}.{j}")));
        }
        names.extend(["kinetic_energy", "potential_energy", "total_energy"].map(String::from));
        names.extend(frames.iter().map(|f| format!("poses.{f}")));
        self.columns = names
            .into_iter()
            .map(|n| {
                let f = tempfile::tempfile().map_err(|e| {
                    Error::io(
                        None,
                        e.kind(),
                        format!("cannot create a temporary file for the run ({e})"),
                    )
                })?;
                Ok((n, std::io::BufWriter::new(f)))
            })
            .collect::<Result<Vec<_>>>()?;
        Ok(())
    }

    fn push(&mut self, s: &Sample) -> Result<()> {
        self.row.clear();
        s.write_values(&mut self.row);
        let scalars = 1 + 4 * self.joints.len() + 3;
        let (plain, frames) = self.columns.split_at_mut(scalars);
        for ((_, spool), x) in plain.iter_mut().zip(&self.row) {
            let text = self.number.json(*x);
            spool.write_all(b",").map_err(io_error)?;
            spool.write_all(text.as_bytes()).map_err(io_error)?;
        }
        for ((_, spool), h) in frames.iter_mut().zip(s.poses) {
            let m = h.to_matrix();
            let rows: Vec<Vec<f64>> = (0..4)
                .map(|r| (0..4).map(|c| m[(r, c)]).collect())
                .collect();
            let text = serde_json::to_string(&rows).map_err(json_error)?;
            write!(spool, ",{text}").map_err(io_error)?;
        }
        self.samples += 1;
        Ok(())
    }

    fn event(&mut self, event: &LimitEvent) -> Result<()> {
        self.events.push(event.to_json().to_string());
        Ok(())
    }
}
