//! The tolerance study: many printed chains, drawn and judged by their margins, in parallel.

use rayon::prelude::*;

use crate::count::Shard;
use crate::margins::{margins, ChainModel, MarginError, MarginOptions, Margins};
use crate::tolerance::{draw_designs, wilson_interval, Tolerances, Z95};
use crate::{Chain, Design, Progress};
use std::sync::atomic::{AtomicU64, Ordering};

/// What a study draws and how. Default: 10,000 samples, seed 1, all of them (no shard),
/// FDM tolerances, the default margins.
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub struct StudyOptions {
    /// Samples in the whole study (a shard draws its share of them).
    pub samples: u64,
    /// The seed.
    pub seed: u64,
    /// Draw only the samples of this part: sample `i` belongs to part `i mod M + 1`.
    pub shard: Option<Shard>,
    /// The tolerances.
    pub tolerances: Tolerances,
    /// How margins are computed.
    pub margins: MarginOptions,
}

impl Default for StudyOptions {
    fn default() -> StudyOptions {
        StudyOptions {
            samples: 10_000,
            seed: 1,
            shard: None,
            tolerances: Tolerances::default(),
            margins: MarginOptions::default(),
        }
    }
}

impl StudyOptions {
    /// Another number of samples in the whole study.
    pub fn with_samples(mut self, samples: u64) -> StudyOptions {
        self.samples = samples;
        self
    }

    /// Another seed.
    pub fn with_seed(mut self, seed: u64) -> StudyOptions {
        self.seed = seed;
        self
    }

    /// Only the samples of part `shard` (`None`: all of them).
    pub fn with_shard(mut self, shard: Option<Shard>) -> StudyOptions {
        self.shard = shard;
        self
    }

    /// Other tolerances.
    pub fn with_tolerances(mut self, tolerances: Tolerances) -> StudyOptions {
        self.tolerances = tolerances;
        self
    }

    /// Other margin options.
    pub fn with_margins(mut self, margins: MarginOptions) -> StudyOptions {
        self.margins = margins;
        self
    }
}

/// How many failing samples began failing at one joint.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub struct FailureCount {
    /// The joint.
    pub joint: usize,
    /// Failing samples whose first failure is there.
    pub count: u64,
}

/// A study's result.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Study {
    /// Samples drawn (this shard's).
    pub samples: u64,
    /// Samples in which the chain folds.
    pub folded: u64,
    /// `folded / samples`.
    pub probability: f64,
    /// The 95% Wilson interval of the probability.
    pub interval: (f64, f64),
    /// Where failures begin, most frequent first.
    pub first_failures: Vec<FailureCount>,
    /// The smallest margin of each sample, summarised: minimum, 5th percentile, median.
    pub smallest_margin: MarginSpread,
    /// The nominal chain's margins (no tolerances).
    #[serde(skip)]
    pub nominal: Margins,
}

impl Study {
    /// Draws the samples of `opts` around the per-tile `nominal` designs (one, or one per
    /// tile) and judges each by its margins.
    pub fn run(
        chain: &Chain,
        nominal: &[Design],
        opts: &StudyOptions,
    ) -> Result<Study, MarginError> {
        study(chain, nominal, opts)
    }

    /// [`Study::run`], saying how many samples are judged (stage `samples`) as it goes.
    ///
    /// ```
    /// use foldchain::tolerance::{Study, StudyOptions};
    /// use foldchain::{Chain, Design};
    /// use std::sync::atomic::{AtomicU64, Ordering};
    ///
    /// let judged = AtomicU64::new(0);
    /// let progress = |_stage: &str, done: u64, _total: u64| {
    ///     judged.fetch_max(done, Ordering::Relaxed);
    /// };
    /// let opts = StudyOptions::default().with_samples(50);
    /// let s = Study::run_reporting(&Chain::parse("SSS").unwrap(), &[Design::thesis()], &opts, &progress).unwrap();
    /// assert_eq!(s.samples, 50);
    /// assert!(judged.load(Ordering::Relaxed) >= 49);
    /// ```
    pub fn run_reporting(
        chain: &Chain,
        nominal: &[Design],
        opts: &StudyOptions,
        progress: &dyn Progress,
    ) -> Result<Study, MarginError> {
        study_reporting(chain, nominal, opts, progress)
    }
}

/// A spread of smallest margins over the samples.
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct MarginSpread {
    /// The smallest.
    pub min: f64,
    /// The 5th percentile.
    pub p05: f64,
    /// The median.
    pub median: f64,
}

struct Outcome {
    folded: bool,
    first_failure: Option<usize>,
    smallest: f64,
}

/// Draws the samples of `opts` around the per-tile `nominal` designs (one, or one per tile)
/// and judges each by its margins.
pub(crate) fn study(
    chain: &Chain,
    nominal: &[Design],
    opts: &StudyOptions,
) -> Result<Study, MarginError> {
    study_reporting(chain, nominal, opts, &())
}

/// [`Study::run_reporting`].
fn study_reporting(
    chain: &Chain,
    nominal: &[Design],
    opts: &StudyOptions,
    progress: &dyn Progress,
) -> Result<Study, MarginError> {
    let nominal_model = ChainModel::new(chain, nominal)?;
    let nominal_margins = margins(&nominal_model, &opts.margins);
    let (k, m) = opts.shard.map_or((0, 1), |s| (s.k as u64 - 1, s.m as u64));
    let indices: Vec<u64> = (k..opts.samples).step_by(m as usize).collect();
    let tiles = chain.len();
    let total = indices.len() as u64;
    let judged = AtomicU64::new(0);
    progress.update("samples", 0, total);
    let outcomes: Vec<Result<Outcome, MarginError>> = indices
        .par_iter()
        .map_init(Vec::new, |designs, &i| {
            let done = judged.fetch_add(1, Ordering::Relaxed);
            progress.update("samples", done, total);
            draw_designs(nominal, tiles, &opts.tolerances, opts.seed, i, designs);
            let model = ChainModel::new(chain, designs)?;
            let mg = margins(&model, &opts.margins);
            let first = mg.first_failure();
            Ok(Outcome {
                folded: first.is_none(),
                first_failure: first.map(|w| w.joint()),
                smallest: mg.weakest().map_or(f64::INFINITY, |w| w.margin()),
            })
        })
        .collect();
    let mut folded = 0;
    let mut counts = vec![0u64; tiles];
    let mut smallest = Vec::with_capacity(outcomes.len());
    for o in outcomes {
        let o = o?;
        folded += u64::from(o.folded);
        if let Some(j) = o.first_failure {
            counts[j] += 1;
        }
        smallest.push(o.smallest);
    }
    let samples = indices.len() as u64;
    let mut first_failures: Vec<FailureCount> = counts
        .iter()
        .enumerate()
        .filter(|(_, &c)| c > 0)
        .map(|(joint, &count)| FailureCount { joint, count })
        .collect();
    first_failures.sort_by(|a, b| b.count.cmp(&a.count).then(a.joint.cmp(&b.joint)));
    smallest.sort_by(f64::total_cmp);
    let pick = |q: f64| {
        smallest
            .get(((smallest.len() as f64 - 1.0) * q).round() as usize)
            .copied()
            .unwrap_or(f64::NAN)
    };
    Ok(Study {
        samples,
        folded,
        probability: if samples > 0 {
            folded as f64 / samples as f64
        } else {
            f64::NAN
        },
        interval: wilson_interval(folded, samples, Z95),
        first_failures,
        smallest_margin: MarginSpread {
            min: pick(0.0),
            p05: pick(0.05),
            median: pick(0.5),
        },
        nominal: nominal_margins,
    })
}
