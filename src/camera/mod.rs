//! The fixed-function matrices of the original labs: `gluPerspective`, `gluLookAt` and
//! `glRotatef`, computed as GLU and Mesa do (GLU in double, the matrix stack in float).
//!
//! GL maps clip-space depth -w..w to 0..1; wgpu expects 0..w. This is the one place that
//! differs: [`gl_to_wgpu_depth`] rewrites only the z row of the projection, so x, y and w — and
//! therefore every pixel's coverage and every interpolated value — are exactly GL's.

use glam::{Mat3, Mat4, Vec3, Vec4};

pub mod fly;
pub mod glm;

/// `gluPerspective(fovy, aspect, near, far)` (GL depth convention, -1..1).
pub fn glu_perspective(fovy_degrees: f64, aspect: f64, near: f64, far: f64) -> Mat4 {
    let radians = fovy_degrees / 2.0 * std::f64::consts::PI / 180.0;
    let delta_z = far - near;
    let sine = radians.sin();
    let cotangent = radians.cos() / sine;
    Mat4::from_cols(
        Vec4::new((cotangent / aspect) as f32, 0.0, 0.0, 0.0),
        Vec4::new(0.0, cotangent as f32, 0.0, 0.0),
        Vec4::new(0.0, 0.0, (-(far + near) / delta_z) as f32, -1.0),
        Vec4::new(0.0, 0.0, (-2.0 * near * far / delta_z) as f32, 0.0),
    )
}

/// Converts a GL projection (depth -w..w) to wgpu's (0..w): z' = (z + w) / 2.
pub fn gl_to_wgpu_depth(projection: Mat4) -> Mat4 {
    let fix = Mat4::from_cols(
        Vec4::new(1.0, 0.0, 0.0, 0.0),
        Vec4::new(0.0, 1.0, 0.0, 0.0),
        Vec4::new(0.0, 0.0, 0.5, 0.0),
        Vec4::new(0.0, 0.0, 0.5, 1.0),
    );
    fix * projection
}

/// GLU's `normalize`: each component divided by the length (not multiplied by its reciprocal,
/// which differs in the last bit), a zero vector left as it is.
fn glu_normalize(v: Vec3) -> Vec3 {
    let r = (v.x * v.x + v.y * v.y + v.z * v.z).sqrt();
    if r == 0.0 {
        v
    } else {
        Vec3::new(v.x / r, v.y / r, v.z / r)
    }
}

/// `gluLookAt(eye, center, up)`, as SGI's GLU computes it (in float).
pub fn glu_look_at(eye: Vec3, center: Vec3, up: Vec3) -> Mat4 {
    let forward = glu_normalize(center - eye);
    let side = glu_normalize(forward.cross(up));
    let up = side.cross(forward);
    let rotation = Mat4::from_cols(
        Vec4::new(side.x, up.x, -forward.x, 0.0),
        Vec4::new(side.y, up.y, -forward.y, 0.0),
        Vec4::new(side.z, up.z, -forward.z, 0.0),
        Vec4::W,
    );
    rotation * Mat4::from_translation(-eye)
}

/// `glRotatef(angle, x, y, z)` for a unit axis, as Mesa builds it.
pub fn gl_rotate(angle_degrees: f32, axis: Vec3) -> Mat4 {
    // Mesa: sinf(angle * M_PI / 180.0), the product in double.
    let radians = (angle_degrees as f64 * std::f64::consts::PI / 180.0) as f32;
    let (s, c) = radians.sin_cos();
    // Mesa's axis-aligned fast paths give exactly these matrices.
    let mut m = Mat4::IDENTITY;
    if axis == Vec3::X {
        m.y_axis = Vec4::new(0.0, c, s, 0.0);
        m.z_axis = Vec4::new(0.0, -s, c, 0.0);
    } else if axis == Vec3::Y {
        m.x_axis = Vec4::new(c, 0.0, -s, 0.0);
        m.z_axis = Vec4::new(s, 0.0, c, 0.0);
    } else if axis == Vec3::Z {
        m.x_axis = Vec4::new(c, s, 0.0, 0.0);
        m.y_axis = Vec4::new(-s, c, 0.0, 0.0);
    } else {
        m = Mat4::from_axis_angle(axis.normalize_or_zero(), radians);
    }
    m
}

/// The object rotation of every lab: `glRotatef(x, 1,0,0); glRotatef(y, 0,1,0); glRotatef(z, 0,0,1)`.
pub fn lab_rotation(angles_degrees: Vec3) -> Mat4 {
    gl_rotate(angles_degrees.x, Vec3::X) * gl_rotate(angles_degrees.y, Vec3::Y) * gl_rotate(angles_degrees.z, Vec3::Z)
}

/// `gl_NormalMatrix`: the inverse transpose of the modelview's upper 3x3.
pub fn normal_matrix(modelview: Mat4) -> Mat3 {
    let m = Mat3::from_mat4(modelview);
    let det = m.determinant();
    if det.abs() < f32::MIN_POSITIVE || !det.is_finite() {
        return Mat3::IDENTITY; // a degenerate modelview has no normal matrix; keep normals finite
    }
    m.inverse().transpose()
}

/// The lab's projection for a viewport (`height == 0` is treated as 1, as the original's resize does),
/// already in wgpu's depth convention.
pub fn lab_projection(width: u32, height: u32) -> Mat4 {
    let height = height.max(1);
    // The original passes `(float) width / height`: a float division, then promoted to double.
    let aspect = (width as f32 / height as f32) as f64;
    gl_to_wgpu_depth(glu_perspective(45.0, aspect, 1.0, 100.0))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn perspective_matches_glu_formula() {
        let p = glu_perspective(45.0, 640.0 / 360.0, 1.0, 100.0);
        let f = 1.0 / (22.5f64.to_radians()).tan();
        assert!((p.y_axis.y as f64 - f).abs() < 1e-6);
        assert!((p.x_axis.x as f64 - f * 360.0 / 640.0).abs() < 1e-6);
        // near plane maps to -1 in GL, to 0 after the depth fix; far to 1 in both
        let near = gl_to_wgpu_depth(p) * Vec4::new(0.0, 0.0, -1.0, 1.0);
        let far = gl_to_wgpu_depth(p) * Vec4::new(0.0, 0.0, -100.0, 1.0);
        assert!((near.z / near.w).abs() < 1e-6);
        assert!((far.z / far.w - 1.0).abs() < 1e-5);
        let gl_near = p * Vec4::new(0.0, 0.0, -1.0, 1.0);
        assert!((gl_near.z / gl_near.w + 1.0).abs() < 1e-6);
    }

    #[test]
    fn depth_fix_keeps_x_y_w() {
        let p = glu_perspective(45.0, 1.5, 1.0, 100.0);
        let q = gl_to_wgpu_depth(p);
        let v = Vec4::new(0.3, -0.7, -4.0, 1.0);
        let (a, b) = (p * v, q * v);
        assert_eq!((a.x, a.y, a.w), (b.x, b.y, b.w));
    }

    #[test]
    fn look_at_normalizes_by_division_as_glu() {
        // gluLookAt((0,1,4), 0, y): forward = (0,-1,-4)/sqrt(17), divided in float as GLU does.
        let m = glu_look_at(Vec3::new(0.0, 1.0, 4.0), Vec3::ZERO, Vec3::Y);
        let r = 17.0f32.sqrt();
        assert_eq!(m.z_axis.z, 4.0 / r);
        assert_eq!(m.y_axis.z, 1.0 / r);
    }

    #[test]
    fn look_at_moves_eye_to_origin() {
        let m = glu_look_at(Vec3::new(0.0, 0.0, 4.0), Vec3::ZERO, Vec3::Y);
        let p = m * Vec4::new(0.0, 0.0, 0.0, 1.0);
        assert!((p - Vec4::new(0.0, 0.0, -4.0, 1.0)).length() < 1e-6);
    }

    #[test]
    fn rotations_follow_gl_conventions() {
        // glRotatef(90, 0,1,0) turns +x into -z; glRotatef(90, 1,0,0) turns +y into +z.
        let y = gl_rotate(90.0, Vec3::Y) * Vec4::new(1.0, 0.0, 0.0, 0.0);
        assert!((y - Vec4::new(0.0, 0.0, -1.0, 0.0)).length() < 1e-6);
        let x = gl_rotate(90.0, Vec3::X) * Vec4::new(0.0, 1.0, 0.0, 0.0);
        assert!((x - Vec4::new(0.0, 0.0, 1.0, 0.0)).length() < 1e-6);
        // Z is applied to the vertex first and X last, as glRotatef X; Y; Z composes them:
        // +x -> (Y 90) -z -> (X 90) +y.
        let r = lab_rotation(Vec3::new(90.0, 90.0, 0.0)) * Vec4::new(1.0, 0.0, 0.0, 0.0);
        assert!((r - Vec4::new(0.0, 1.0, 0.0, 0.0)).length() < 1e-6, "{r}");
        // And not the other order: Ry(90) Rx(90) would send +x to -z.
        let swapped = gl_rotate(90.0, Vec3::Y) * gl_rotate(90.0, Vec3::X) * Vec4::new(1.0, 0.0, 0.0, 0.0);
        assert!((swapped - r).length() > 1.0);
    }

    #[test]
    fn zero_height_is_treated_as_one() {
        assert_eq!(lab_projection(640, 0), lab_projection(640, 1));
        assert!(lab_projection(640, 0).is_finite());
    }
}
