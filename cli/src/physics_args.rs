//! The physical parameters on the command line (`--magnet-mass`, `--tile-mass`, `--drag`,
//! `--friction`, `--restitution`, `--viscosity`, `--water-film`, `--form-drag`,
//! `--water-density`): each
//! overrides the design file's field of the same meaning (`foldchain::Design`), for every
//! model the tool runs.

use foldchain::timeline::TileDesigns;
use foldchain::Design;

use crate::numbers::in_range;

/// The physical parameters a command line may set (clap flattens them into a tool's
/// arguments).
#[derive(clap::Args, Debug, Clone, Default)]
pub struct PhysicsArgs {
    /// Magnet mass, g (default: the design's, 0.265 g: a 3 x 5 mm NdFeB cylinder).
    #[arg(long, value_name = "G", value_parser = in_range(1e-6, 1e5, "g", ""), allow_hyphen_values = true)]
    pub magnet_mass: Option<f64>,
    /// Mass of a tile without its magnets, g (default: the design's, 3 g).
    #[arg(long, value_name = "G", value_parser = in_range(1e-6, 1e5, "g", ""), allow_hyphen_values = true)]
    pub tile_mass: Option<f64>,
    /// Drag of a magnet in its channel, N s/m, for every model and the kinematic speed law
    /// (default: the design's, else 0.05 inertial and 5 overdamped).
    #[arg(long, value_name = "N_S_PER_M", value_parser = in_range(1e-3, 1e4, "N s/m", ""), allow_hyphen_values = true)]
    pub drag: Option<f64>,
    /// Coulomb friction of a magnet in its channel, N (default 0).
    #[arg(long, value_name = "N", value_parser = in_range(0.0, 10.0, "N", ""), allow_hyphen_values = true)]
    pub friction: Option<f64>,
    /// Coefficient of restitution of a magnet at its path's end or a fold at its walls
    /// (default 0.3).
    #[arg(long, value_parser = in_range(0.0, 0.99, "", "a bounce loses energy"), allow_hyphen_values = true)]
    pub restitution: Option<f64>,
    /// Dynamic viscosity of the water, Pa s (default 1e-3).
    #[arg(long, value_name = "PA_S", value_parser = in_range(1e-5, 100.0, "Pa s", "from air to honey"), allow_hyphen_values = true)]
    pub viscosity: Option<f64>,
    /// Thickness of the sheared water under a tile, mm (default 0.25).
    #[arg(long, value_name = "MM", value_parser = in_range(1e-3, 1000.0, "mm", ""), allow_hyphen_values = true)]
    pub water_film: Option<f64>,
    /// Form drag coefficient of a tile's immersed edge (default 0: none; only the free-body
    /// reference with inertial dynamics integrates it).
    #[arg(long, value_name = "CD", value_parser = in_range(0.0, 10.0, "", "a plate broadside has about 2"), allow_hyphen_values = true)]
    pub form_drag: Option<f64>,
    /// Density of the water, kg/m^3 (default 998): a tile's draft and its form drag.
    #[arg(long, value_name = "KG_PER_M3", value_parser = in_range(1.0, 20_000.0, "kg/m^3", "from air to mercury"), allow_hyphen_values = true)]
    pub water_density: Option<f64>,
}

impl PhysicsArgs {
    /// `designs` with the parameters given set on the global design.
    pub fn apply(&self, designs: TileDesigns) -> TileDesigns {
        let p = self.clone();
        designs.with_global(|d: &mut Design| {
            let set = |field: &mut f64, v: Option<f64>| {
                if let Some(v) = v {
                    *field = v;
                }
            };
            set(&mut d.magnet_mass, p.magnet_mass);
            set(&mut d.tile_mass, p.tile_mass);
            if p.drag.is_some() {
                d.magnet_drag = p.drag;
            }
            set(&mut d.friction, p.friction);
            set(&mut d.restitution, p.restitution);
            set(&mut d.water_viscosity, p.viscosity);
            set(&mut d.water_film, p.water_film);
            set(&mut d.form_drag, p.form_drag);
            set(&mut d.water_density, p.water_density);
        })
    }

    /// The options given, by name (for a tool that refuses them).
    pub fn given(&self) -> Vec<&'static str> {
        [
            ("--magnet-mass", self.magnet_mass),
            ("--tile-mass", self.tile_mass),
            ("--drag", self.drag),
            ("--friction", self.friction),
            ("--restitution", self.restitution),
            ("--viscosity", self.viscosity),
            ("--water-film", self.water_film),
            ("--form-drag", self.form_drag),
            ("--water-density", self.water_density),
        ]
        .into_iter()
        .filter_map(|(name, v)| v.map(|_| name))
        .collect()
    }
}
