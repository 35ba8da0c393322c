//! Seed 002, Lecture 12 (P. Khungurn): twisting and double vision in 2D, and the teapot of
//! [`geometry`] with normals and Phong in world space.

pub mod geometry;

pub mod double_vision;
pub mod normal_world;
pub mod phong_dir;
pub mod twist;

lecture!("002 Lecture 12", (512, 512));
