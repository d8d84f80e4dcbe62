//! The physical parameters a run used ([`Parameters`]), as `summary.json` states them: the
//! model and its dynamics, the pair law, every mass, drag and property of the water, and
//! the tile design, resolved (a default filled in is stated as the value used).

/// The parameters of a run.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct Parameters {
    /// Which model integrated the run: `event engine` (the joint-angle model one joint at a
    /// time), `joint-angle reference`, `free-body reference` or `kinematic baseline`.
    pub model: &'static str,
    /// `overdamped` or `inertial` (`kinematic` for the baseline).
    pub dynamics: &'static str,
    /// The pair law (`dipole` or `cylinder`).
    pub force_law: &'static str,
    /// Pairs at most this many apart in chain index interact.
    pub cutoff: usize,
    /// Pairs nearer than this interact whatever their chain index, mm (null: none).
    pub distance_cutoff_mm: Option<f64>,
    /// Mass of a magnet, g.
    pub magnet_mass_g: f64,
    /// Mass of a tile without its magnets, g.
    pub tile_mass_g: f64,
    /// A tile's moment of inertia about its centre, magnets excluded, kg m^2.
    pub tile_inertia_kg_m2: f64,
    /// Drag of a magnet in its channel, N s/m.
    pub magnet_drag_n_s_per_m: f64,
    /// Coulomb friction of a magnet in its channel, N.
    pub friction_n: f64,
    /// Coefficient of restitution at a wall.
    pub restitution: f64,
    /// Viscosity of the water, Pa s.
    pub water_viscosity_pa_s: f64,
    /// Thickness of the sheared water under a tile, mm.
    pub water_film_mm: f64,
    /// Density of the water, kg/m^3.
    pub water_density_kg_m3: f64,
    /// Form drag coefficient of a tile's edge (0: none).
    pub form_drag_cd: f64,
    /// A tile's linear drag translating on the water, N s/m.
    pub tile_drag_n_s_per_m: f64,
    /// A tile's linear drag turning about its centre on the water, N m s.
    pub tile_rotational_drag_n_m_s: f64,
    /// The tile design of the chain's first tile as the run used it, defaults filled in:
    /// `tile_width_mm`, `d_mm`, `s_mm`, `e_mm`, `c_mm` (only where the design sets it; else
    /// the wall places the magnets' final points), `wall_mm`, `magnet_diameter_mm`,
    /// `magnet_height_mm`, `remanence_t` (a design file's per-tile overrides are not listed;
    /// the masses, drags and water are the fields above).
    pub design: std::collections::BTreeMap<&'static str, f64>,
}

/// [`Parameters::design`] of the design `d`.
pub(crate) fn design_parameters(
    d: &crate::Design,
) -> std::collections::BTreeMap<&'static str, f64> {
    let mut m: std::collections::BTreeMap<&'static str, f64> = [
        ("tile_width_mm", d.tile_width),
        ("d_mm", d.d),
        ("s_mm", d.s),
        ("e_mm", d.e),
        ("wall_mm", d.wall),
        ("magnet_diameter_mm", d.magnet_diameter),
        ("magnet_height_mm", d.magnet_height),
        ("remanence_t", d.remanence),
    ]
    .into_iter()
    .collect();
    if let Some(c) = d.c {
        m.insert("c_mm", c);
    }
    m
}
