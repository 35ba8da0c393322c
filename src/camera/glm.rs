//! The matrices of GLM (0.9.9, right-handed, GL depth -1..1), in f32 with GLM's order of
//! operations, for the programs that build their matrices with `glm::perspective`,
//! `glm::lookAt`, `glm::rotate` and `glm::inverse` instead of GLU and the GL matrix stack
//! (seed 004). Apply [`super::gl_to_wgpu_depth`] to the projection as for GLU's.

use glam::{Mat3, Mat4, Vec3, Vec4};

/// `glm::radians(degrees)` for a float: `degrees * (float)0.01745329251994329576923690768489`.
pub fn radians(degrees: f32) -> f32 {
    degrees * (std::f64::consts::PI / 180.0) as f32
}

/// `glm::perspective(fovy, aspect, near, far)` (fovy in radians), all in f32:
/// `tanHalfFovy = tan(fovy / 2)`, `1 / (aspect * tanHalfFovy)`, `1 / tanHalfFovy`,
/// `-(far + near) / (far - near)`, `-1`, `-(2 * far * near) / (far - near)`.
pub fn perspective(fovy: f32, aspect: f32, near: f32, far: f32) -> Mat4 {
    let tan_half_fovy = (fovy / 2.0).tan();
    Mat4::from_cols(
        Vec4::new(1.0 / (aspect * tan_half_fovy), 0.0, 0.0, 0.0),
        Vec4::new(0.0, 1.0 / tan_half_fovy, 0.0, 0.0),
        Vec4::new(0.0, 0.0, -(far + near) / (far - near), -1.0),
        Vec4::new(0.0, 0.0, -(2.0 * far * near) / (far - near), 0.0),
    )
}

/// GLM's `normalize`: `v * inversesqrt(dot(v, v))`.
fn normalize(v: Vec3) -> Vec3 {
    v * (1.0 / v.dot(v).sqrt())
}

/// `glm::lookAt(eye, center, up)`: f = normalize(center − eye), s = normalize(f × up),
/// u = s × f, translation −s·eye, −u·eye, f·eye.
pub fn look_at(eye: Vec3, center: Vec3, up: Vec3) -> Mat4 {
    let f = normalize(center - eye);
    let s = normalize(f.cross(up));
    let u = s.cross(f);
    Mat4::from_cols(
        Vec4::new(s.x, u.x, -f.x, 0.0),
        Vec4::new(s.y, u.y, -f.y, 0.0),
        Vec4::new(s.z, u.z, -f.z, 0.0),
        Vec4::new(-s.dot(eye), -u.dot(eye), f.dot(eye), 1.0),
    )
}

/// `glm::rotate(m, angle, axis)` (radians): GLM's general rotation matrix (c + (1 − c)·a·a on
/// the diagonal even for a coordinate axis, so cos and 1 − cos do not always add up to 1
/// exactly) multiplied into `m`'s first three columns.
pub fn rotate(m: Mat4, angle: f32, axis: Vec3) -> Mat4 {
    let (s, c) = (angle.sin(), angle.cos());
    let axis = normalize(axis);
    let temp = (1.0 - c) * axis;
    let r = [
        [
            c + temp.x * axis.x,
            temp.x * axis.y + s * axis.z,
            temp.x * axis.z - s * axis.y,
        ],
        [
            temp.y * axis.x - s * axis.z,
            c + temp.y * axis.y,
            temp.y * axis.z + s * axis.x,
        ],
        [
            temp.z * axis.x + s * axis.y,
            temp.z * axis.y - s * axis.x,
            c + temp.z * axis.z,
        ],
    ];
    let column = |k: usize| m.x_axis * r[k][0] + m.y_axis * r[k][1] + m.z_axis * r[k][2];
    Mat4::from_cols(column(0), column(1), column(2), m.w_axis)
}

/// `glm::inverse` of a mat3: the cofactors times `1 / det`, det expanded along the first
/// column as GLM writes it. A singular matrix gives non-finite values, as in GLM.
pub fn inverse3(m: Mat3) -> Mat3 {
    let a = m.to_cols_array_2d(); // a[col][row], GLM's m[col][row]
    let one_over_det = 1.0
        / (a[0][0] * (a[1][1] * a[2][2] - a[2][1] * a[1][2]) - a[1][0] * (a[0][1] * a[2][2] - a[2][1] * a[0][2])
            + a[2][0] * (a[0][1] * a[1][2] - a[1][1] * a[0][2]));
    let mut inv = [[0.0f32; 3]; 3];
    inv[0][0] = (a[1][1] * a[2][2] - a[2][1] * a[1][2]) * one_over_det;
    inv[1][0] = -(a[1][0] * a[2][2] - a[2][0] * a[1][2]) * one_over_det;
    inv[2][0] = (a[1][0] * a[2][1] - a[2][0] * a[1][1]) * one_over_det;
    inv[0][1] = -(a[0][1] * a[2][2] - a[2][1] * a[0][2]) * one_over_det;
    inv[1][1] = (a[0][0] * a[2][2] - a[2][0] * a[0][2]) * one_over_det;
    inv[2][1] = -(a[0][0] * a[2][1] - a[2][0] * a[0][1]) * one_over_det;
    inv[0][2] = (a[0][1] * a[1][2] - a[1][1] * a[0][2]) * one_over_det;
    inv[1][2] = -(a[0][0] * a[1][2] - a[1][0] * a[0][2]) * one_over_det;
    inv[2][2] = (a[0][0] * a[1][1] - a[1][0] * a[0][1]) * one_over_det;
    Mat3::from_cols_array_2d(&inv)
}

/// The course's normal matrix `transpose(inverse(mat3(MV)))`.
pub fn normal_matrix(modelview: Mat4) -> Mat3 {
    inverse3(Mat3::from_mat4(modelview)).transpose()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn perspective_is_the_glu_frustum() {
        let p = perspective(radians(45.0), 640.0 / 480.0, 0.1, 100.0);
        let glu = super::super::glu_perspective(45.0, f64::from(640.0f32 / 480.0), 0.1, 100.0);
        assert!(p.abs_diff_eq(glu, 1e-5), "{p} vs {glu}");
        assert_eq!(p.z_axis.w, -1.0);
    }

    #[test]
    fn look_at_and_rotate_match_the_exact_matrices() {
        let v = look_at(Vec3::new(0.0, 0.0, 4.0), Vec3::ZERO, Vec3::Y);
        assert_eq!(v, Mat4::from_translation(Vec3::new(0.0, 0.0, -4.0)));
        let glu = super::super::glu_look_at(Vec3::new(0.0, 0.5, 3.0), Vec3::new(0.0, -1.0, -3.0), Vec3::Y);
        assert!(look_at(Vec3::new(0.0, 0.5, 3.0), Vec3::new(0.0, -1.0, -3.0), Vec3::Y).abs_diff_eq(glu, 1e-6));
        // rotate(I, 90°, y) turns +x into -z; rotate(rotate(I, a, x), b, y) = Rx(a)·Ry(b).
        let y = rotate(Mat4::IDENTITY, radians(90.0), Vec3::Y) * Vec4::X;
        assert!((y - Vec4::new(0.0, 0.0, -1.0, 0.0)).length() < 1e-6);
        let m = rotate(rotate(Mat4::IDENTITY, radians(30.0), Vec3::X), radians(45.0), Vec3::Y);
        let exact = Mat4::from_rotation_x(30f32.to_radians()) * Mat4::from_rotation_y(45f32.to_radians());
        assert!(m.abs_diff_eq(exact, 1e-6));
    }

    #[test]
    fn normal_matrix_is_the_inverse_transpose() {
        let mv = look_at(Vec3::new(0.0, 0.0, 4.0), Vec3::ZERO, Vec3::Y)
            * rotate(Mat4::IDENTITY, 0.3, Vec3::new(1.0, 2.0, 3.0))
            * Mat4::from_scale(Vec3::new(1.0, 2.0, 0.5));
        let nm = normal_matrix(mv);
        let expect = Mat3::from_mat4(mv).inverse().transpose();
        assert!(nm.abs_diff_eq(expect, 1e-5), "{nm} vs {expect}");
    }
}
