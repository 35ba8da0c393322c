//! The free-flying camera of seed 003 (LETI lab 5, Qt), SPEC §3, with Qt's float arithmetic:
//! `QVector3D` in f32 and Qt 6's `normalize()` rule ([`qt_normalize`]).
//!
//! [`FlyCamera::view`] is `QMatrix4x4::lookAt`, the same matrix as `gluLookAt`
//! ([`super::glu_look_at`]); [`FlyCamera::projection`] is `QMatrix4x4::perspective` in GL's
//! depth convention — convert it with [`super::gl_to_wgpu_depth`] for wgpu.

use glam::{Mat4, Vec3, Vec4};

/// Qt 6 `QVector3D::normalize()`: len = hypot(x, y, z) as a float (computed in double, rounded);
/// the vector is returned unchanged if |len − 1| ≤ 1e-5 or len ≤ 1e-5 (`qFuzzyIsNull`), else
/// each component is divided by len in float. A zero vector stays zero.
pub fn qt_normalize(v: Vec3) -> Vec3 {
    let (x, y, z) = (f64::from(v.x), f64::from(v.y), f64::from(v.z));
    let len = (x * x + y * y + z * z).sqrt() as f32;
    if (len - 1.0).abs() <= 1e-5 || len.abs() <= 1e-5 {
        return v;
    }
    Vec3::new(v.x / len, v.y / len, v.z / len)
}

/// `qDegreesToRadians(float)`: degrees · (float)(π/180).
fn radians(degrees: f32) -> f32 {
    degrees * (std::f64::consts::PI / 180.0) as f32
}

/// A [`FlyCamera::move_`] direction (the report's `Camera::Direction`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Move {
    /// +front.
    Forward,
    /// −front.
    Back,
    /// −right, right = normalize(front × up).
    Left,
    /// +right.
    Right,
    /// +up.
    Up,
    /// −up.
    Down,
}

/// The report's `Camera` class: position, direction and field of view, all in float.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FlyCamera {
    /// Eye position (`pos`).
    pub position: Vec3,
    /// Viewing direction, unit length.
    pub front: Vec3,
    /// The up vector, (0, 1, 0).
    pub up: Vec3,
    /// Yaw in degrees (−90 looks down −z).
    pub yaw: f32,
    /// Pitch in degrees, kept in [−89, 89].
    pub pitch: f32,
    /// Vertical field of view in degrees.
    pub fov: f32,
}

impl Default for FlyCamera {
    fn default() -> Self {
        Self::new()
    }
}

impl FlyCamera {
    /// Distance of one [`Self::move_`] step.
    pub const SPEED: f32 = 0.5;
    /// Near plane of [`Self::projection`].
    pub const NEAR: f32 = 0.1;
    /// Far plane of [`Self::projection`].
    pub const FAR: f32 = 50.0;

    /// The constructor: position (0, 0, 3), front (0, 0, −1), up (0, 1, 0), yaw −90, pitch 0,
    /// fov 45.
    pub fn new() -> FlyCamera {
        FlyCamera {
            position: Vec3::new(0.0, 0.0, 3.0),
            front: Vec3::new(0.0, 0.0, -1.0),
            up: Vec3::new(0.0, 1.0, 0.0),
            yaw: -90.0,
            pitch: 0.0,
            fov: 45.0,
        }
    }

    /// What the report's `initializeGL` does to the camera: `rotate(30, 0)`, then
    /// `move(Left)` three times, leaving it at (−1.299038, 0, 2.25) looking at the origin.
    pub fn initialize_gl(&mut self) {
        self.rotate(30.0, 0.0);
        for _ in 0..3 {
            self.move_(Move::Left);
        }
    }

    /// `move(dir)`: one step of [`Self::SPEED`] along front, right = normalize(front × up)
    /// or up.
    pub fn move_(&mut self, direction: Move) {
        let right = qt_normalize(self.front.cross(self.up));
        let step = |v: Vec3| Self::SPEED * v;
        match direction {
            Move::Forward => self.position += step(self.front),
            Move::Back => self.position -= step(self.front),
            Move::Left => self.position -= step(right),
            Move::Right => self.position += step(right),
            Move::Up => self.position += step(self.up),
            Move::Down => self.position -= step(self.up),
        }
    }

    /// `rotate(dyaw, dpitch)`: yaw += dyaw, pitch += dpitch clamped to [−89, 89], then
    /// front = normalize(cos yaw · cos pitch, sin pitch, sin yaw · cos pitch) (degrees → radians
    /// in float).
    pub fn rotate(&mut self, dyaw: f32, dpitch: f32) {
        self.yaw += dyaw;
        self.pitch = (self.pitch + dpitch).clamp(-89.0, 89.0);
        let (yaw, pitch) = (radians(self.yaw), radians(self.pitch));
        self.front = qt_normalize(Vec3::new(yaw.cos() * pitch.cos(), pitch.sin(), yaw.sin() * pitch.cos()));
    }

    /// `getView`: lookAt(position, position + front, up).
    pub fn view(&self) -> Mat4 {
        super::glu_look_at(self.position, self.position + self.front, self.up)
    }

    /// `getProjection`: `QMatrix4x4::perspective(fov, aspect, 0.1, 50)` in float, GL depth
    /// (−1..1). A zero or non-finite aspect gives the identity, as Qt leaves the matrix alone.
    pub fn projection(&self, aspect: f32) -> Mat4 {
        let (near, far) = (Self::NEAR, Self::FAR);
        let angle = radians(self.fov / 2.0);
        let sine = angle.sin();
        if aspect == 0.0 || !aspect.is_finite() || sine == 0.0 {
            return Mat4::IDENTITY;
        }
        let cotan = angle.cos() / sine;
        let clip = far - near;
        Mat4::from_cols(
            Vec4::new(cotan / aspect, 0.0, 0.0, 0.0),
            Vec4::new(0.0, cotan, 0.0, 0.0),
            Vec4::new(0.0, 0.0, -(near + far) / clip, -1.0),
            Vec4::new(0.0, 0.0, -(2.0 * near * far) / clip, 0.0),
        )
    }
}

/// A start state of the camera as SPEC §3 names its states: what `initializeGL` leaves
/// (or the bare constructor, `preset`), then `up` × move(Up), `forward` × move(Forward),
/// `right` × move(Right) (negative counts move Down, Back, Left), then one
/// `rotate(yaw, pitch)` if either is non-zero.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct FlyStart {
    /// Skip `initializeGL`'s `rotate(30, 0)` and three `move(Left)` (the constructor camera).
    pub preset: bool,
    /// Steps of move(Up) (negative: Down).
    pub up: i32,
    /// Steps of move(Forward) (negative: Back).
    pub forward: i32,
    /// Steps of move(Right) (negative: Left).
    pub right: i32,
    /// Yaw change of the final rotate, degrees.
    pub yaw: f32,
    /// Pitch change of the final rotate, degrees (the pitch clamp applies).
    pub pitch: f32,
}

impl FlyCamera {
    /// The camera in a [`FlyStart`] state, the operations applied in SPEC §3's order.
    pub fn from_start(start: &FlyStart) -> FlyCamera {
        let mut camera = FlyCamera::new();
        if !start.preset {
            camera.initialize_gl();
        }
        let steps = [
            (start.up, Move::Up, Move::Down),
            (start.forward, Move::Forward, Move::Back),
            (start.right, Move::Right, Move::Left),
        ];
        for (count, positive, negative) in steps {
            let direction = if count < 0 { negative } else { positive };
            for _ in 0..count.unsigned_abs() {
                camera.move_(direction);
            }
        }
        if start.yaw != 0.0 || start.pitch != 0.0 {
            camera.rotate(start.yaw, start.pitch);
        }
        camera
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: Vec3, b: Vec3, tol: f32) -> bool {
        (a - b).abs().max_element() <= tol
    }

    #[test]
    fn qt_normalize_rule() {
        assert_eq!(qt_normalize(Vec3::ZERO), Vec3::ZERO);
        assert_eq!(qt_normalize(Vec3::new(3.0, 0.0, 4.0)), Vec3::new(0.6, 0.0, 0.8));
        // Within 1e-5 of unit length: unchanged.
        let near_unit = Vec3::new(1.000004, 0.0, 0.0);
        assert_eq!(qt_normalize(near_unit), near_unit);
        let tiny = Vec3::new(1e-6, 0.0, 0.0);
        assert_eq!(qt_normalize(tiny), tiny);
        assert_eq!(qt_normalize(Vec3::new(0.0, 2.0, 0.0)), Vec3::Y);
    }

    #[test]
    fn initialize_gl_looks_at_origin() {
        let mut c = FlyCamera::new();
        assert_eq!(
            (c.position, c.front, c.yaw, c.pitch, c.fov),
            (Vec3::new(0.0, 0.0, 3.0), -Vec3::Z, -90.0, 0.0, 45.0)
        );
        c.initialize_gl();
        assert!(
            close(c.position, Vec3::new(-1.299038, 0.0, 2.25), 1e-5),
            "{}",
            c.position
        );
        assert!(close(c.front, Vec3::new(0.5, 0.0, -0.866025), 1e-5), "{}", c.front);
        assert_eq!(c.yaw, -60.0);
        // The origin is straight ahead: view space (0, 0, -|pos|).
        let o = c.view() * Vec4::new(0.0, 0.0, 0.0, 1.0);
        assert!(
            o.x.abs() < 1e-5 && o.y.abs() < 1e-5 && (o.z + 2.598076).abs() < 1e-5,
            "{o}"
        );
    }

    #[test]
    fn moves_and_pitch_clamp() {
        let mut c = FlyCamera::new();
        c.move_(Move::Forward);
        assert_eq!(c.position, Vec3::new(0.0, 0.0, 2.5));
        c.move_(Move::Up);
        c.move_(Move::Right);
        assert_eq!(c.position, Vec3::new(0.5, 0.5, 2.5));
        c.move_(Move::Back);
        c.move_(Move::Down);
        c.move_(Move::Left);
        assert_eq!(c.position, Vec3::new(0.0, 0.0, 3.0));
        for _ in 0..100 {
            c.rotate(0.0, 2.0);
        }
        assert_eq!(c.pitch, 89.0);
        assert!(c.front.y > 0.9998 && c.front.y < 1.0);
        c.rotate(0.0, -500.0);
        assert_eq!(c.pitch, -89.0);
        // State "above": up=2 then pitch -30 after initializeGL.
        let mut a = FlyCamera::new();
        a.initialize_gl();
        a.move_(Move::Up);
        a.move_(Move::Up);
        a.rotate(0.0, -30.0);
        assert!(close(a.position, Vec3::new(-1.299038, 1.0, 2.25), 1e-5));
        assert!((a.front.y + 0.5).abs() < 1e-6);
    }

    #[test]
    fn projection_is_qt_perspective() {
        let c = FlyCamera::new();
        let p = c.projection(640.0 / 480.0);
        let f = 1.0 / (22.5f64.to_radians()).tan();
        assert!((f64::from(p.y_axis.y) - f).abs() < 1e-5);
        assert!((f64::from(p.x_axis.x) - f * 0.75).abs() < 1e-5);
        // Near plane to -1, far plane to +1 (GL depth).
        let near = p * Vec4::new(0.0, 0.0, -0.1, 1.0);
        let far = p * Vec4::new(0.0, 0.0, -50.0, 1.0);
        assert!((near.z / near.w + 1.0).abs() < 1e-5 && (far.z / far.w - 1.0).abs() < 1e-5);
        assert_eq!(c.projection(0.0), Mat4::IDENTITY);
        assert_eq!(c.projection(f32::NAN), Mat4::IDENTITY);
    }

    #[test]
    fn start_states_follow_spec_order() {
        let mut init = FlyCamera::new();
        init.initialize_gl();
        assert_eq!(FlyCamera::from_start(&FlyStart::default()), init);
        assert_eq!(
            FlyCamera::from_start(&FlyStart {
                preset: true,
                ..FlyStart::default()
            }),
            FlyCamera::new()
        );
        // "above": up=2 pitch=-30.
        let above = FlyCamera::from_start(&FlyStart {
            up: 2,
            pitch: -30.0,
            ..FlyStart::default()
        });
        assert!(close(above.position, Vec3::new(-1.299038, 1.0, 2.25), 1e-5));
        assert!((above.front.y + 0.5).abs() < 1e-6 && above.yaw == -60.0);
        // "closer": forward=3 yaw=-10: the moves use the front before the rotation.
        let closer = FlyCamera::from_start(&FlyStart {
            forward: 3,
            yaw: -10.0,
            ..FlyStart::default()
        });
        assert!(close(closer.position, init.position + 1.5 * init.front, 1e-6));
        assert_eq!(closer.yaw, -70.0);
        // Negative counts go the other way; the pitch clamp holds.
        let back = FlyCamera::from_start(&FlyStart {
            preset: true,
            forward: -2,
            right: -1,
            up: -1,
            pitch: 120.0,
            ..FlyStart::default()
        });
        assert_eq!(back.position, Vec3::new(-0.5, -0.5, 4.0));
        assert_eq!(back.pitch, 89.0);
    }
}
