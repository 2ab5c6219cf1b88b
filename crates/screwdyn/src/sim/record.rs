//! [`Recording`]: what a simulation or torque profile produced, sample by sample, with CSV and
//! JSON output whose column names follow DESIGN §5.

use crate::spatial::Se3;
use std::io::Write;

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
    /// Potential energy in gravity (J).
    pub potential_energy: Vec<f64>,
    /// Their sum (J).
    pub total_energy: Vec<f64>,
    /// Names of the recorded frames.
    pub frames: Vec<String>,
    /// Poses of the recorded frames, one vector (in `frames` order) per sample.
    pub poses: Vec<Vec<Se3>>,
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

    /// Number of samples.
    pub fn len(&self) -> usize {
        self.t.len()
    }

    /// Whether there is no sample.
    pub fn is_empty(&self) -> bool {
        self.t.is_empty()
    }

    /// Column names: `t`, `q.<joint>`…, `v.<joint>`…, `a.<joint>`…, `tau.<joint>`…,
    /// `kinetic_energy`, `potential_energy`, `total_energy`, then `pose.<frame>.x|y|z` per frame.
    pub fn columns(&self) -> Vec<String> {
        let mut c = vec!["t".to_string()];
        for key in ["q", "v", "a", "tau"] {
            c.extend(self.joints.iter().map(|j| format!("{key}.{j}")));
        }
        c.extend(["kinetic_energy", "potential_energy", "total_energy"].map(String::from));
        for f in &self.frames {
            c.extend(["x", "y", "z"].map(|k| format!("pose.{f}.{k}")));
        }
        c
    }

    /// Writes one CSV row per sample under [`Recording::columns`].
    ///
    /// ```
    /// let mut r = screwdyn::sim::Recording::new(vec!["j1".into()], vec![]);
    /// r.push(0.5, &[1.0], &[2.0], &[3.0], &[4.0], (1.0, 2.0), vec![]);
    /// let mut out = Vec::new();
    /// r.write_csv(&mut out).unwrap();
    /// let text = String::from_utf8(out).unwrap();
    /// assert_eq!(text.lines().next().unwrap(), "t,q.j1,v.j1,a.j1,tau.j1,kinetic_energy,potential_energy,total_energy");
    /// assert_eq!(text.lines().nth(1).unwrap(), "0.5,1,2,3,4,1,2,3");
    /// ```
    pub fn write_csv(&self, w: &mut impl Write) -> std::io::Result<()> {
        writeln!(w, "{}", self.columns().join(","))?;
        for k in 0..self.len() {
            let mut row = vec![self.t[k]];
            for x in [&self.q, &self.v, &self.a, &self.tau] {
                row.extend_from_slice(&x[k]);
            }
            row.extend([
                self.kinetic_energy[k],
                self.potential_energy[k],
                self.total_energy[k],
            ]);
            if let Some(p) = self.poses.get(k) {
                for h in p {
                    row.extend(h.translation.iter());
                }
            }
            let cells: Vec<String> = row.iter().map(|x| x.to_string()).collect();
            writeln!(w, "{}", cells.join(","))?;
        }
        Ok(())
    }

    /// The recording as JSON: the same names as the CSV columns, each holding an array over
    /// samples (`q.<joint>` etc.), plus `joints`, `t` and, per frame, `poses.<frame>` as 4×4
    /// row-major matrices.
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
        serde_json::Value::Object(m)
    }

    /// Appends one sample.
    #[allow(clippy::too_many_arguments)]
    pub fn push(
        &mut self,
        t: f64,
        q: &[f64],
        v: &[f64],
        a: &[f64],
        tau: &[f64],
        energy: (f64, f64),
        poses: Vec<Se3>,
    ) {
        self.t.push(t);
        self.q.push(q.to_vec());
        self.v.push(v.to_vec());
        self.a.push(a.to_vec());
        self.tau.push(tau.to_vec());
        self.kinetic_energy.push(energy.0);
        self.potential_energy.push(energy.1);
        self.total_energy.push(energy.0 + energy.1);
        if !self.frames.is_empty() {
            self.poses.push(poses);
        }
    }
}
