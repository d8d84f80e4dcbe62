//! A run's `margins.json`: the drive margin of every magnet's start and the torque margin of
//! every fold ([`foldchain::margins`]), the smallest of them and where, for chains up to
//! [`MAX_MARGIN_TILES`] tiles.

use foldchain::margins::{MarginOptions, Margins, Weakest};
use foldchain::physics::ForceLaw;
use foldchain::timeline::TileDesigns;
use foldchain::{Chain, Design};

/// The longest chain whose margins a run writes: about 50 us per tile, a second here.
pub const MAX_MARGIN_TILES: usize = 20_000;

/// What `margins.json` says, with the criterion in words.
#[derive(serde::Serialize)]
struct MarginsFile<'a> {
    criterion: &'static str,
    force_law: ForceLaw,
    smallest: Option<Weakest>,
    first_failure: Option<Weakest>,
    #[serde(flatten)]
    margins: &'a Margins,
}

/// The criterion the margins judge by, as the files and tools state it.
pub const CRITERION: &str = "margins are fractions of the tile's bond force (starts) or of the bond force times the pair's lever about the hinge (folds), on quasi-static poses (docs/tolerances.md, Margins); the chain folds as designed when every one is positive (holds: the resting chain keeps each magnet in place before the RI comes)";

/// The margins of `chain` with `designs` under `law`, and their JSON text; `None` for a chain
/// longer than [`MAX_MARGIN_TILES`] or one whose paths cannot be built.
pub fn run_margins(
    chain: &Chain,
    designs: &TileDesigns,
    law: ForceLaw,
) -> Option<(Margins, String)> {
    if chain.len() > MAX_MARGIN_TILES || chain.is_empty() {
        return None;
    }
    let (list, index) = designs.resolve(chain.len());
    let per_tile: Vec<Design> = if index.is_empty() {
        vec![list[0]]
    } else {
        index.iter().map(|&i| list[i as usize]).collect()
    };
    let m = Margins::of(
        chain,
        &per_tile,
        &MarginOptions::default().with_force_law(law),
    )
    .ok()?;
    let file = MarginsFile {
        criterion: CRITERION,
        force_law: law,
        smallest: m.weakest(),
        first_failure: m.first_failure(),
        margins: &m,
    };
    let mut text = serde_json::to_string_pretty(&file).ok()?;
    text.push('\n');
    Some((m, text))
}

/// [`run_margins`] on a second thread, so that a run's margins are worked out while the
/// engine runs: started with the chain, finished when the run's files are written.
pub struct MarginsJob(std::thread::JoinHandle<Option<(Margins, String)>>);

impl MarginsJob {
    /// Starts [`run_margins`] of `chain` with `designs` under `law`.
    pub fn start(chain: &Chain, designs: &TileDesigns, law: ForceLaw) -> MarginsJob {
        let (chain, designs) = (chain.clone(), designs.clone());
        MarginsJob(std::thread::spawn(move || {
            run_margins(&chain, &designs, law)
        }))
    }

    /// What [`run_margins`] returned (waiting for it; a panic there is raised here).
    pub fn finish(self) -> Option<(Margins, String)> {
        self.0
            .join()
            .unwrap_or_else(|panic| std::panic::resume_unwind(panic))
    }
}
