//! Robot descriptions: URDF, DH tables, product of exponentials, native TOML; URDF export.
