//! # foldchain-cli
//!
//! The command-line tools of `foldchain`: `fold-plan`, `fold-run`, `fold-check`, `fold-enum`,
//! `fold-validate`, `fold-tolerance` and `fold-print` (in `src/bin/`), and the pieces they
//! share: writing outputs without touching anything the tools did not write ([`output`], [`record`]),
//! writing a run's pictures and JSON into its output directory ([`run_files`]), reading a
//! chain named on the command line ([`chain_arg`]) and guarding input files ([`inputs`]), the
//! thesis' experiments ([`experiments`]), progress on stderr ([`progress`]), a run's margins
//! ([`margins_file`]), its name ([`run_name`]), the named choices of the options
//! ([`choices`]), the physical parameters ([`physics_args`]) and error messages ([`report`]). The libraries `foldchain` and
//! `foldchain-planner` compute; this crate parses, prints, writes and exits.
//!
//! Install all seven tools with `cargo install --path cli` from the repository root.

pub mod chain_arg;
pub mod choices;
pub mod experiments;
pub mod fold_run;
pub mod help;
pub mod inputs;
pub mod margins_file;
pub mod numbers;
pub mod output;
pub mod physics_args;
pub mod progress;
pub mod record;
pub mod report;
pub mod run_dir;
pub mod run_files;
pub mod run_name;
pub mod stdout;
