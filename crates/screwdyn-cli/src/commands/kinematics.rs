//! `fk` and `jacobian`.

use super::{load, parse_vector};
use crate::args::{FkArgs, Format, JacobianArgs, ReferenceArg};
use crate::output::{matrix_json, matrix_rows, resolve};
use crate::CliError;
use nalgebra::{DMatrix, Matrix6xX};
use screwdyn::kinematics::{
    compute_joint_jacobians, forward_kinematics, frame_jacobian, frame_pose, Reference,
};
use screwdyn::Workspace;

/// `screwdyn fk MODEL --q ... [--frame NAME]`.
pub fn fk(a: &FkArgs) -> Result<(), CliError> {
    let m = load(&a.model.model)?;
    let q = parse_vector(a.q.as_deref(), "q", &m)?;
    let frames: Vec<usize> = match &a.frame {
        Some(name) => vec![m.frame_id(name)?],
        None => (0..m.frames().len()).collect(),
    };
    let mut ws = Workspace::new(&m);
    forward_kinematics(&m, &mut ws, &q)?;
    let poses: Vec<(String, DMatrix<f64>)> = frames
        .iter()
        .map(|&f| {
            let h = frame_pose(&m, &ws, f).to_matrix();
            (
                m.frames()[f].name.clone(),
                DMatrix::from_iterator(4, 4, h.iter().copied()),
            )
        })
        .collect();
    match resolve(a.model.format) {
        Format::Json => {
            let map: serde_json::Map<String, serde_json::Value> = poses
                .iter()
                .map(|(n, h)| (n.clone(), matrix_json(h)))
                .collect();
            let v = serde_json::json!({"joints": m.joint_names(), "q": q, "poses": map});
            println!(
                "{}",
                serde_json::to_string_pretty(&v).expect("JSON of numbers")
            );
        }
        Format::Csv => {
            println!("frame,r11,r12,r13,px,r21,r22,r23,py,r31,r32,r33,pz");
            for (n, h) in &poses {
                let row: Vec<String> = (0..3)
                    .flat_map(|r| (0..4).map(move |c| (r, c)))
                    .map(|(r, c)| h[(r, c)].to_string())
                    .collect();
                println!("{n},{}", row.join(","));
            }
        }
        Format::Table => {
            for (n, h) in &poses {
                println!("H_{n}^0 =\n{}\n", matrix_rows(h));
            }
        }
    }
    Ok(())
}

/// `screwdyn jacobian MODEL --frame NAME --q ... [--reference ...]`.
pub fn jacobian(a: &JacobianArgs) -> Result<(), CliError> {
    let m = load(&a.model.model)?;
    let q = parse_vector(a.q.as_deref(), "q", &m)?;
    let f = match &a.frame {
        Some(name) => m.frame_id(name)?,
        None => m.frames().len() - 1,
    };
    let reference = match a.reference {
        ReferenceArg::World => Reference::World,
        ReferenceArg::Local => Reference::Local,
        ReferenceArg::WorldAligned => Reference::LocalWorldAligned,
    };
    let mut ws = Workspace::new(&m);
    compute_joint_jacobians(&m, &mut ws, &q)?;
    let mut j = Matrix6xX::zeros(m.nq());
    frame_jacobian(&m, &ws, f, reference, &mut j);
    let j = DMatrix::from_iterator(6, m.nq(), j.iter().copied());
    let name = &m.frames()[f].name;
    match resolve(a.model.format) {
        Format::Json => {
            let v = serde_json::json!({"joints": m.joint_names(), "frame": name, "q": q, "jacobian": matrix_json(&j)});
            println!(
                "{}",
                serde_json::to_string_pretty(&v).expect("JSON of numbers")
            );
        }
        Format::Csv => {
            println!("row,{}", m.joint_names().join(","));
            for (r, label) in ["wx", "wy", "wz", "vx", "vy", "vz"].iter().enumerate() {
                let row: Vec<String> = (0..m.nq()).map(|c| j[(r, c)].to_string()).collect();
                println!("{label},{}", row.join(","));
            }
        }
        Format::Table => {
            println!(
                "Jacobian of frame '{name}' ({:?}), rows ω then v, columns {}:",
                a.reference,
                m.joint_names().join(", ")
            );
            println!("{}", matrix_rows(&j));
        }
    }
    Ok(())
}
