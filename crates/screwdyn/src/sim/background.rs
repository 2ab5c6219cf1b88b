//! [`BackgroundSink`]: a [`SampleSink`] run on a second thread, so that turning samples into
//! text (the shortest round-trip digits of every number) and writing them overlaps the
//! integration instead of adding to it.

use super::limit_events::LimitEvent;
use super::record::{Sample, SampleSink};
use crate::error::{Error, Result};
use crate::spatial::Se3;
use std::sync::mpsc::{channel, sync_channel, Receiver, SyncSender};
use std::thread::JoinHandle;

/// Samples per message to the worker: the channel's cost is shared by this many samples.
const SAMPLES_PER_BATCH: usize = 64;
/// Batches on their way to the worker at most: a run of any length holds bounded memory, and
/// a simulator faster than its writer waits for it.
const BATCHES_IN_FLIGHT: usize = 4;

/// Samples copied out of the simulator: per sample, `t, q, q̇, q̈, τ, T, V` in `values` and
/// the frame poses in `poses`.
#[derive(Default)]
struct Batch {
    values: Vec<f64>,
    poses: Vec<Se3>,
    samples: usize,
}

enum Message {
    Begin(Vec<String>, Vec<String>),
    Samples(Batch),
    Event(LimitEvent),
}

/// A [`SampleSink`] that hands its samples, in batches, to `inner` on a worker thread:
/// the simulator only copies each sample's numbers, and the worker formats and writes them
/// while the next steps are integrated. Samples and events reach `inner` in the order they were
/// sent; [`BackgroundSink::finish`] waits for all of them and returns `inner`.
///
/// An error of `inner` stops the worker; the simulator receives it at its next sample (or from
/// `finish`), so a run writing to a full disk still stops early.
///
/// ```
/// use screwdyn::sim::{simulate_into, BackgroundSink, CsvSampleWriter, SimOptions, ZeroTorque};
/// let m = screwdyn::builtin::pendulum();
/// let opts = SimOptions { duration: 0.25, dt: 0.1, ..Default::default() };
/// let mut sink = BackgroundSink::new(CsvSampleWriter::new(Vec::new()));
/// simulate_into(&m, &[0.1], &[0.0], &mut ZeroTorque, &[], &opts, &mut sink, &mut |_| {}).unwrap();
/// let text = String::from_utf8(sink.finish().unwrap().into_inner()).unwrap();
/// assert_eq!(text.lines().count(), 5); // the header and samples at 0, 0.1, 0.2, 0.25 s
/// assert!(text.lines().last().unwrap().starts_with("0.25,"));
/// ```
pub struct BackgroundSink<S> {
    to_worker: Option<SyncSender<Message>>,
    /// Batches the worker has emptied, to be filled again (no allocation per batch).
    spare: Receiver<Batch>,
    batch: Batch,
    /// Joints and recorded frames, from `begin`.
    shape: (usize, usize),
    worker: Option<JoinHandle<(S, Result<()>)>>,
}

impl<S: SampleSink + Send + 'static> BackgroundSink<S> {
    /// Starts the worker thread that will feed `inner`.
    pub fn new(inner: S) -> Self {
        let (to_worker, from_main) = sync_channel::<Message>(BATCHES_IN_FLIGHT);
        let (to_main, spare) = channel::<Batch>();
        let worker = std::thread::spawn(move || {
            let mut inner = inner;
            let result = feed(&mut inner, &from_main, &to_main);
            (inner, result)
        });
        BackgroundSink {
            to_worker: Some(to_worker),
            spare,
            batch: Batch::default(),
            shape: (0, 0),
            worker: Some(worker),
        }
    }

    /// Waits until the worker has passed every sample and event to `inner`, and returns it.
    ///
    /// # Errors
    /// The first error of `inner`.
    pub fn finish(mut self) -> Result<S> {
        // A failed send has already collected the worker and answers with its error.
        self.send_batch()?;
        self.to_worker = None;
        let (inner, result) = self.join()?;
        result.map(|()| inner)
    }

    /// Sends the current batch (if it holds samples), reusing an emptied one.
    fn send_batch(&mut self) -> Result<()> {
        if self.batch.samples == 0 {
            return Ok(());
        }
        let next = self.spare.try_recv().unwrap_or_default();
        let full = std::mem::replace(&mut self.batch, next);
        self.send(Message::Samples(full))
    }

    fn send(&mut self, m: Message) -> Result<()> {
        let sent = match &self.to_worker {
            Some(tx) => tx.send(m).is_ok(),
            None => false,
        };
        if sent {
            return Ok(());
        }
        // The worker has stopped: `inner` failed (or panicked); its error is the answer.
        self.to_worker = None;
        match self.join()?.1 {
            Err(e) => Err(e),
            Ok(()) => Err(stopped()),
        }
    }

    fn join(&mut self) -> Result<(S, Result<()>)> {
        let worker = self.worker.take().ok_or_else(stopped)?;
        worker.join().map_err(|_| stopped())
    }
}

/// The error when the worker is gone without an error of its own.
#[cold]
fn stopped() -> Error {
    Error::io(
        None,
        std::io::ErrorKind::Other,
        "the thread writing the samples stopped",
    )
}

/// The worker: passes every message to `inner` until the simulator side hangs up or `inner`
/// fails, and returns each emptied batch.
fn feed<S: SampleSink>(
    inner: &mut S,
    from_main: &Receiver<Message>,
    to_main: &std::sync::mpsc::Sender<Batch>,
) -> Result<()> {
    let (mut n, mut frames) = (0, 0);
    for m in from_main {
        match m {
            Message::Begin(joints, frame_names) => {
                (n, frames) = (joints.len(), frame_names.len());
                inner.begin(&joints, &frame_names)?;
            }
            Message::Event(e) => inner.event(&e)?,
            Message::Samples(mut b) => {
                let width = 4 * n + 3;
                for k in 0..b.samples {
                    let x = &b.values[k * width..(k + 1) * width];
                    inner.push(&Sample {
                        t: x[0],
                        q: &x[1..1 + n],
                        v: &x[1 + n..1 + 2 * n],
                        a: &x[1 + 2 * n..1 + 3 * n],
                        tau: &x[1 + 3 * n..1 + 4 * n],
                        kinetic_energy: x[1 + 4 * n],
                        potential_energy: x[2 + 4 * n],
                        poses: &b.poses[k * frames..(k + 1) * frames],
                    })?;
                }
                b.values.clear();
                b.poses.clear();
                b.samples = 0;
                // The simulator may have finished; then the batch is simply dropped.
                let _ = to_main.send(b);
            }
        }
    }
    Ok(())
}

impl<S: SampleSink + Send + 'static> SampleSink for BackgroundSink<S> {
    fn begin(&mut self, joints: &[String], frames: &[String]) -> Result<()> {
        self.shape = (joints.len(), frames.len());
        self.send(Message::Begin(joints.to_vec(), frames.to_vec()))
    }

    fn push(&mut self, s: &Sample) -> Result<()> {
        let (n, frames) = self.shape;
        let lens = [s.q.len(), s.v.len(), s.a.len(), s.tau.len()];
        if lens.iter().any(|&l| l != n) || s.poses.len() != frames {
            return Err(Error::InvalidArgument(format!(
                "a sample with q, q̇, q̈, τ of {lens:?} values and {} poses does not fit a run of {n} joints and {frames} frames",
                s.poses.len()
            )));
        }
        let b = &mut self.batch;
        b.values.push(s.t);
        for x in [s.q, s.v, s.a, s.tau] {
            b.values.extend_from_slice(x);
        }
        b.values.extend([s.kinetic_energy, s.potential_energy]);
        b.poses.extend_from_slice(s.poses);
        b.samples += 1;
        if b.samples == SAMPLES_PER_BATCH {
            self.send_batch()?;
        }
        Ok(())
    }

    fn event(&mut self, e: &LimitEvent) -> Result<()> {
        // The samples before the event go first.
        self.send_batch()?;
        self.send(Message::Event(e.clone()))
    }
}

impl<S> Drop for BackgroundSink<S> {
    fn drop(&mut self) {
        // Without `finish`: hang up, and let the worker end on its own.
        self.to_worker = None;
    }
}
