//! Point and line loads on vertex groups ([`Simulation::add_load`](crate::Simulation::add_load)).

use std::mem::MaybeUninit;

use progsim_sys as sys;

/// How a load's force is spread over its vertex group.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum LoadDistribution {
    /// f_i = F m_i / Σ m_j by lumped vertex mass (`PS_LOAD_BY_MASS`).
    #[default]
    Mass,
    /// f_i = F A_i / Σ A_j by lumped vertex area, a third of each incident face's
    /// (`PS_LOAD_BY_AREA`).
    Area,
    /// f_i = F on every vertex of the group (`PS_LOAD_PER_VERTEX`).
    PerVertex,
}

impl LoadDistribution {
    fn to_raw(self) -> sys::ps_load_distribution {
        match self {
            LoadDistribution::Mass => sys::PS_LOAD_BY_MASS,
            LoadDistribution::Area => sys::PS_LOAD_BY_AREA,
            LoadDistribution::PerVertex => sys::PS_LOAD_PER_VERTEX,
        }
    }
}

/// A point or line load on a vertex group, grown linearly from 0 over `ramp` seconds of simulated
/// time: a force and a moment (a couple of forces summing to zero) fixed in direction and size
/// (potential −Σ f_i·x_i), and a normal force that follows the surface. The default is no load on no vertices.
#[derive(Clone, Debug, PartialEq)]
pub struct Load {
    /// Index of the scene's body; default 0.
    pub body: i32,
    /// The group: vertex indices within the body's mesh (each counted once); required.
    pub vertices: Vec<i32>,
    /// N: the total, or the force on each vertex with [`LoadDistribution::PerVertex`];
    /// default zero.
    pub force: [f64; 3],
    /// How `force` is spread; default [`LoadDistribution::Mass`].
    pub distribution: LoadDistribution,
    /// Direction of the moment (any non-zero length); default +z.
    pub moment_axis: [f64; 3],
    /// N·m; default 0 (none). Weighted like the force (equally with `PerVertex`); the group
    /// must not lie on one line along the axis.
    pub moment: f64,
    /// N along the unit vertex normals (the faces' winding), spread like the force and turning
    /// with the surface (a follower load); default 0 (none). Single-level simulations only.
    pub normal_force: f64,
    /// s, ≥ 0; default 0 (the full load at once).
    pub ramp: f64,
    /// The group as a region instead of `vertices` (which must then be empty): the body's
    /// vertices inside the axis-aligned box `[min, max]` (m, boundary included). On VPD
    /// levels, which share no vertices, each level takes its own vertices inside it. Default
    /// `None`.
    pub region: Option<[[f64; 3]; 2]>,
}

impl Default for Load {
    fn default() -> Load {
        let raw = raw_load_def();
        Load {
            body: raw.body,
            vertices: Vec::new(),
            force: raw.force,
            distribution: LoadDistribution::Mass,
            moment_axis: raw.moment_axis,
            moment: raw.moment,
            normal_force: raw.normal_force,
            ramp: raw.ramp,
            region: None,
        }
    }
}

/// The C defaults, filled by `ps_load_def_init()`.
fn raw_load_def() -> sys::ps_load_def {
    let mut raw = MaybeUninit::<sys::ps_load_def>::uninit();
    // SAFETY: ps_load_def_init() fills every field of a non-NULL def.
    unsafe {
        sys::ps_load_def_init(raw.as_mut_ptr());
        raw.assume_init()
    }
}

impl Load {
    /// The C def borrowing `self.vertices` and `self.region`: valid while `self` is.
    pub(crate) fn to_raw(&self) -> sys::ps_load_def {
        let mut raw = raw_load_def();
        raw.body = self.body;
        raw.vertices = self.vertices.as_ptr();
        raw.num_vertices = self.vertices.len();
        raw.force = self.force;
        raw.distribution = self.distribution.to_raw();
        raw.moment_axis = self.moment_axis;
        raw.moment = self.moment;
        raw.normal_force = self.normal_force;
        raw.ramp = self.ramp;
        if let Some([min, max]) = &self.region {
            raw.box_min = min.as_ptr();
            raw.box_max = max.as_ptr();
        }
        raw
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn defaults_are_the_c_library_defaults() {
        let load = Load::default();
        assert_eq!((load.body, load.moment, load.ramp), (0, 0.0, 0.0));
        assert_eq!(load.normal_force, 0.0);
        assert_eq!(load.moment_axis, [0.0, 0.0, 1.0]);
        assert_eq!(load.distribution, LoadDistribution::Mass);
        assert!(load.vertices.is_empty() && load.region.is_none());
        let raw = load.to_raw();
        assert!(raw.box_min.is_null() && raw.box_max.is_null());
    }

    #[test]
    fn raw_def_carries_every_field() {
        let load = Load {
            body: 1,
            vertices: vec![2, 7],
            force: [1.0, 2.0, 3.0],
            distribution: LoadDistribution::PerVertex,
            moment_axis: [0.0, 1.0, 0.0],
            moment: 4.0,
            normal_force: -6.0,
            ramp: 0.5,
            region: Some([[-1.0, -2.0, -3.0], [1.0, 2.0, 3.0]]),
        };
        let raw = load.to_raw();
        let region = load.region.as_ref().unwrap();
        assert_eq!((raw.box_min, raw.box_max), (region[0].as_ptr(), region[1].as_ptr()));
        assert_eq!((raw.body, raw.num_vertices), (1, 2));
        assert_eq!(raw.vertices, load.vertices.as_ptr());
        assert_eq!(raw.force, [1.0, 2.0, 3.0]);
        assert_eq!(raw.distribution, sys::PS_LOAD_PER_VERTEX);
        assert_eq!((raw.moment_axis, raw.moment, raw.ramp), ([0.0, 1.0, 0.0], 4.0, 0.5));
        assert_eq!(raw.normal_force, -6.0);
    }
}
