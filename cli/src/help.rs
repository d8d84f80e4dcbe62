//! The help texts of the tools (`--help`): what each does and examples of its use, in one
//! place so that the binaries' argument structs stay short.

/// `fold-check`: what the tool does (the first line of `--help`).
pub const CHECK_ABOUT: &str = "Does a chain of tiles fold without hitting itself? Checks every fold sweep (sequential folding from the reaction-initiator end) and the final shape.";

/// `fold-check`: examples and exit codes (the end of `--help`).
pub const CHECK_AFTER_HELP: &str = "Examples:
  fold-check SLLS                  a tight U-turn: valid
  fold-check LSLLSR                collision: tiles 0 and 6 meet while joint 3 folds
  fold-check --final-only LSLLSR   valid: the final shape is clean, the sweep is not
  fold-check 'SS SL LL LS SS' --json
  fold-check chain.txt             a file holding a word, a tile list or JSON
  fold-check key-plan.json         a plan written by fold-plan --out (its tiles)

Exit codes: 0 valid, 1 collides or propagation inhibited, 2 bad input.";

/// `fold-enum`: what the tool does (the first line of `--help`).
pub const ENUM_ABOUT: &str = "Counts the fold words whose chains fold without self-intersection, for every chain length (thesis Table 5.1), from the geometry and the exact sweep check; optionally the chance that a chain of random tiles folds.";

/// `fold-enum`: examples and exit codes (the end of `--help`).
pub const ENUM_AFTER_HELP: &str = "Examples:
  fold-enum --max-tiles 6                 thesis Table 5.1: 3 7 17 35 79
  fold-enum --max-tiles 20 --json
  fold-enum --max-tiles 12 --random       with the probability for random tiles
  fold-enum --max-tiles 26 --shard 3/8 --json > part-3.json
                                          part 3 of 8 of the search (parts add up)
  fold-enum --merge part-*.json           the whole count from all 8 parts

The count grows about twice per tile: a run expected to take more than a few minutes says
so before it starts. On a terminal a progress bar appears after a second; otherwise a
progress line is printed every few seconds (--quiet silences both).

Exit codes: 0 done, 2 bad input.";

/// `fold-plan`: what the tool does (the first line of `--help`).
pub const PLAN_ABOUT: &str = "Plans the chain of tiles that folds into a shape drawn in SVG: serpentine rows joined by U-turns, monotone cells joined by turns; every plan is checked to fold without self-intersection.";

/// `fold-plan`: examples and exit codes (the end of `--help`).
pub const PLAN_AFTER_HELP: &str = "Examples:
  fold-plan shapes/square.svg --tiles 107 --turns tight
  fold-plan shapes/key.svg --tiles 171 --preview key-plan.svg --out key-plan.json
  fold-plan shapes/ring.svg --tiles 300 --json
  fold-run --plan key-plan.json     fold the planned chain

Prints the run-length tile list and a summary line (or the plan JSON with --json).
Progress goes to stderr (plain lines every few seconds when stderr is not a terminal;
--quiet silences). Limits: at most 2,000,000 tiles and 10,000,000 outline points; outlines of many points are simplified to 1/1000 of the drawing first.
Exit codes: 0 planned, 1 the shape cannot be planned (the reason is given), 2 bad input.";

/// `fold-run`: what the tool does (the first line of `--help`).
pub const RUN_ABOUT: &str = "Folds a chain of tiles: when every magnet moves and every joint folds (the event engine, or the force-integrated reference with --reference), whether two tiles collide on the way, and the pictures and JSON of the run.";

/// `fold-run`: examples and exit codes (the end of `--help`).
pub const RUN_AFTER_HELP: &str = "Examples:
  fold-run SLLS                         a straight tile, a tight U-turn, a straight tile
  fold-run \"S*4 L L S*4 R R S*4\" --json
  fold-run shapes/key.svg --tiles 171   plan the shape, then fold it
  fold-run --plan key-plan.json --design my-design.json
  fold-run LSLLSR --s e/3 --frames 60 --out out/lsllsr
  fold-run SLLS --reference             the force-integrated reference (up to 2,000 tiles)
  fold-run LSLLSR --compare             engine and reference side by side in one page

Writes into --out DIR (default out/NAME/): step-NNNN.svg frames, final.svg, transition.svg,
energy.svg, index.html (the animated viewer: open it in a browser; #t=SECONDS opens it at
that time), timeline.json, margins.json (the margin of every start and fold, chains up to
20,000 tiles) and summary.json. The run is written beside DIR and swapped into place at the
end: DIR holds the earlier run or the new one, whole, whatever happens; a second run into
DIR meanwhile is refused; files of yours in DIR are kept. Times are simulated seconds.
The design JSON is described in docs/designing.md (see also docs/design-example.json).
Limits: 2,000,000 tiles (the engine; about 1 GB of memory, BENCHMARKS.md), 2,000 (--reference,
--compare; 100,000 with --model free-body).

Exit codes: 0 folded completely and cleanly, 1 collided, inhibited, stalled or undecided,
2 bad input, 3 the disk is full (DIR left as it was).";
