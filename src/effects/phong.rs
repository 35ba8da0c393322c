//! Exercise 3, Phong per-pixel lighting (`Lab05-3`): an orange object lit by one point light
//! given in eye space, `Ka*ambient + Kd*diffuse*max(N·L,0) + Ks*specular*pow(max(R·E,0), shininess)`
//! with `R = normalize(-reflect(L, N))`, on a dark blue background. The light is drawn as a small
//! white sphere (visible once it is in front of the camera).
//!
//! Keys: `W/A/S/D` move the camera by 0.1 (and the eye-space light the opposite way, so it stays
//! put in the world); `X/Y/Z` +0.1 and `x/y/z` -0.1 on the light; `<`/`>` Ka ∓0.05; `[`/`]` Kd
//! ∓0.05; `{`/`}` Ks ∓0.05; `H`/`h` shininess ±1 within [6, 200]; `R/G/B` +0.01 and `r/g/b`
//! -0.01 on the diffuse colour; `m` cycles the shading model (flat, Gouraud, Phong, Blinn-Phong;
//! a port addition, the original has Phong only). Coefficients and colours clamp to [0, 1]; the light and camera
//! coordinates to [-50, 50].

use glam::Vec3;

use super::step;
use crate::effect::{Effect, Scene, Shading};

/// Exercise 3.
pub struct Phong;

/// The `PhongParams` block of `phong_params.glsl` (std140: each vec3 shares 16 bytes with the float after it).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct PhongUniforms {
    /// `lightPosition`, eye space.
    pub light_position: [f32; 3],
    /// `Ka`.
    pub ka: f32,
    /// `ambientColor`.
    pub ambient_color: [f32; 3],
    /// `Kd`.
    pub kd: f32,
    /// `diffuseColor`.
    pub diffuse_color: [f32; 3],
    /// `Ks`.
    pub ks: f32,
    /// `specularColor`.
    pub specular_color: [f32; 3],
    /// `shininess`.
    pub shininess: f32,
}
crate::uniform_block!(PhongUniforms, "PhongParams", {
    light_position: "lightPosition",
    ka: "Ka",
    ambient_color: "ambientColor",
    kd: "Kd",
    diffuse_color: "diffuseColor",
    ks: "Ks",
    specular_color: "specularColor",
    shininess: "shininess",
});

impl Default for PhongUniforms {
    fn default() -> Self {
        PhongUniforms {
            light_position: [0.0, 1.0, 1.0],
            ka: 0.1,
            ambient_color: [0.1, 0.1, 0.1],
            kd: 1.0,
            diffuse_color: [1.0, 0.5, 0.0],
            ks: 1.0,
            specular_color: [1.0, 1.0, 1.0],
            shininess: 32.0,
        }
    }
}

/// Bound on light and camera coordinates.
const REACH: f32 = 50.0;

impl Effect for Phong {
    type Uniforms = PhongUniforms;
    const NAME: &'static str = "phong";
    const TITLE: &'static str = "Lab05-3";
    const LABEL: &'static str = "Phong";
    const CLEAR: [f64; 3] = [0.05, 0.1, 0.2];
    const CAMERA: Vec3 = Vec3::new(0.0, 0.0, 5.0);
    const LIGHT_MARKER: bool = true;
    const MOVABLE_CAMERA: bool = true;
    const SHADING_MODELS: bool = true;

    fn shader_files(shading: Shading) -> (String, String) {
        let (vert, frag) = match shading {
            Shading::Flat => ("phong.vert", "phong_flat.frag"),
            Shading::Gouraud => ("phong_gouraud.vert", "phong_gouraud.frag"),
            Shading::Phong => ("phong.vert", "phong.frag"),
            Shading::Blinn => ("phong.vert", "phong_blinn.frag"),
        };
        (vert.into(), frag.into())
    }

    fn defaults() -> PhongUniforms {
        PhongUniforms::default()
    }

    fn key(key: char, u: &mut PhongUniforms, scene: &mut Scene) -> bool {
        let light = &mut u.light_position;
        let mut camera = |dx: f32, dz: f32, light: &mut [f32; 3]| {
            scene.camera.x = (scene.camera.x + dx).clamp(-REACH, REACH);
            scene.camera.z = (scene.camera.z + dz).clamp(-REACH, REACH);
            step(&mut light[0], -dx, -REACH, REACH);
            step(&mut light[2], -dz, -REACH, REACH);
        };
        match key {
            'a' | 'A' => camera(-0.1, 0.0, light),
            'd' | 'D' => camera(0.1, 0.0, light),
            'w' | 'W' => camera(0.0, -0.1, light),
            's' | 'S' => camera(0.0, 0.1, light),
            'X' => step(&mut light[0], 0.1, -REACH, REACH),
            'Y' => step(&mut light[1], 0.1, -REACH, REACH),
            'Z' => step(&mut light[2], 0.1, -REACH, REACH),
            'x' => step(&mut light[0], -0.1, -REACH, REACH),
            'y' => step(&mut light[1], -0.1, -REACH, REACH),
            'z' => step(&mut light[2], -0.1, -REACH, REACH),
            'R' => step(&mut u.diffuse_color[0], 0.01, 0.0, 1.0),
            'G' => step(&mut u.diffuse_color[1], 0.01, 0.0, 1.0),
            'B' => step(&mut u.diffuse_color[2], 0.01, 0.0, 1.0),
            'r' => step(&mut u.diffuse_color[0], -0.01, 0.0, 1.0),
            'g' => step(&mut u.diffuse_color[1], -0.01, 0.0, 1.0),
            'b' => step(&mut u.diffuse_color[2], -0.01, 0.0, 1.0),
            'H' => step(&mut u.shininess, 1.0, 6.0, 200.0),
            'h' => step(&mut u.shininess, -1.0, 6.0, 200.0),
            '[' => step(&mut u.kd, -0.05, 0.0, 1.0),
            ']' => step(&mut u.kd, 0.05, 0.0, 1.0),
            '{' => step(&mut u.ks, -0.05, 0.0, 1.0),
            '}' => step(&mut u.ks, 0.05, 0.0, 1.0),
            '<' => step(&mut u.ka, -0.05, 0.0, 1.0),
            '>' => step(&mut u.ka, 0.05, 0.0, 1.0),
            _ => return false,
        }
        true
    }

    fn light_position(u: &PhongUniforms) -> Option<Vec3> {
        Some(Vec3::from_array(u.light_position))
    }

    fn summary(u: &PhongUniforms) -> String {
        // Keys step in f32, so +0.1 then -0.1 can leave -0.00000001: show it as 0.0, not -0.0.
        let [lx, ly, lz] = u.light_position.map(|c| if c.abs() < 0.05 { 0.0 } else { c });
        let [r, g, b] = u.diffuse_color;
        format!(
            "light ({lx:.1},{ly:.1},{lz:.1}) Ka {:.2} Kd {:.2} Ks {:.2} shininess {:.0} diffuse ({r:.2},{g:.2},{b:.2})",
            u.ka, u.kd, u.ks, u.shininess
        )
    }
}
