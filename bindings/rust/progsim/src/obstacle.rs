//! Collision objects from code: obstacles ([`Simulation::add_obstacle`]) and the analytic
//! ground ([`Simulation::set_ground`]).
//!
//! [`Simulation::add_obstacle`]: crate::Simulation::add_obstacle
//! [`Simulation::set_ground`]: crate::Simulation::set_ground

use std::mem::MaybeUninit;

use progsim_sys as sys;

/// A triangle mesh moved rigidly by a script, not simulated (scene key `obstacles`). The
/// default has no mesh.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Obstacle {
    /// World positions at t = 0, m.
    pub vertices: Vec<[f64; 3]>,
    /// Vertex indices of each triangle.
    pub faces: Vec<[i32; 3]>,
    /// Coulomb μ of its surface, in [0, 10]; default 0.
    pub friction: f64,
    /// Coarse levels of a PSQ simulation meet a decimated copy, refined with the shell
    /// (PSQ §4.6); default false.
    pub progressive: bool,
}

impl Obstacle {
    /// The C def borrowing `self`'s arrays: valid while `self` is.
    pub(crate) fn to_raw(&self) -> sys::ps_obstacle_def {
        let mut raw = MaybeUninit::<sys::ps_obstacle_def>::uninit();
        // SAFETY: ps_obstacle_def_init() fills every field of a non-NULL def.
        let mut raw = unsafe {
            sys::ps_obstacle_def_init(raw.as_mut_ptr());
            raw.assume_init()
        };
        raw.vertices = self.vertices.as_ptr().cast::<f64>();
        raw.num_vertices = self.vertices.len();
        raw.faces = self.faces.as_ptr().cast::<i32>();
        raw.num_faces = self.faces.len();
        raw.friction = self.friction;
        raw.progressive = i32::from(self.progressive);
        raw
    }
}

/// The analytic ground: the half-space n·x ≥ `height` (scene key `ground`). The default is the
/// plane y = 0 without friction.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ground {
    /// n, pointing to the free side (any non-zero length); default +y.
    pub normal: [f64; 3],
    /// m, the plane's offset along n; default 0.
    pub height: f64,
    /// Coulomb μ, in [0, 10]; default 0.
    pub friction: f64,
}

impl Default for Ground {
    fn default() -> Ground {
        Ground { normal: [0.0, 1.0, 0.0], height: 0.0, friction: 0.0 }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn raw_def_borrows_the_mesh_and_carries_every_field() {
        let obstacle = Obstacle {
            vertices: vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]],
            faces: vec![[0, 1, 2]],
            friction: 0.4,
            progressive: true,
        };
        let raw = obstacle.to_raw();
        assert_eq!((raw.num_vertices, raw.num_faces), (3, 1));
        assert_eq!(raw.vertices, obstacle.vertices.as_ptr().cast::<f64>());
        assert_eq!(raw.faces, obstacle.faces.as_ptr().cast::<i32>());
        assert_eq!((raw.friction, raw.progressive), (0.4, 1));
        assert_ne!(raw.internal_cookie, 0);
    }
}
