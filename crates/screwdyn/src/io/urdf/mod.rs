//! URDF: loading ([`parse_urdf`]) and export of any [`Model`](crate::Model)
//! ([`to_urdf_string`]).
//!
//! Mapping (docs/formats.md): a joint's frame is its child link's frame, so `<origin>` is
//! `H_c^p(0)` and `<axis>` (any direction, normalised; a zero axis is an error) is written in
//! the child frame: `S_c^{c,p} = (axis, 0)` for revolute/continuous joints, `(0, axis)` for
//! prismatic ones. `<inertial>` gives the CoM (`origin xyz`) and the inertia about it in axes
//! rotated by `origin rpy`: `I_c = R I Rᵀ`. Fixed joints merge the child into its parent body
//! and keep the link as a named frame. Joints are numbered depth-first from the root link,
//! children in file order. `<visual>`/`<collision>` are ignored except for their mesh file
//! names, kept in [`Model::meshes`](crate::Model::meshes). `<mimic>` is recorded but the joint
//! stays an independent coordinate (as in Pinocchio). A `<limit>` attribute that is absent
//! means "no limit". Floating and planar joints are rejected.
//!
//! ```
//! use screwdyn::io::{urdf::{parse_urdf, to_urdf_string}, LoadOptions};
//! let text = r#"<robot name="r">
//!   <link name="base"/>
//!   <link name="arm"><inertial><mass value="2"/><inertia ixx="0.1" iyy="0.1" izz="0.1" ixy="0" ixz="0" iyz="0"/></inertial></link>
//!   <joint name="j" type="revolute"><parent link="base"/><child link="arm"/>
//!     <origin xyz="0 0 1"/><axis xyz="0 0 2"/><limit lower="-1" upper="1" effort="5" velocity="2"/></joint>
//! </robot>"#;
//! let m = parse_urdf(text, "r.urdf", &LoadOptions::default()).unwrap();
//! assert_eq!(m.joints()[0].screw.as_slice(), &[0.0, 0.0, 1.0, 0.0, 0.0, 0.0]);
//! let again = parse_urdf(&to_urdf_string(&m).unwrap(), "again.urdf", &LoadOptions::default()).unwrap();
//! assert_eq!(again.joints()[0].limits, m.joints()[0].limits);
//!
//! let e = parse_urdf("<robot name='r'><link name='a'/>", "bad.urdf", &LoadOptions::default()).unwrap_err();
//! assert!(e.to_string().starts_with("bad.urdf:1:"));
//! ```

mod export;
mod parse;
mod visuals;

pub use export::{to_urdf_string, urdf_export_warnings};
pub use parse::parse_urdf;
pub use visuals::parse_visuals;
