//! The margins' verdict against the force-integrated reference: where every margin is
//! clearly positive the reference folds the chain completely, where one is clearly negative
//! it stalls, and at the magnet the margins name.
#![allow(clippy::unwrap_used)] // tests may unwrap (CONTRIBUTING)

use foldchain::margins::{MarginOptions, Margins, Weakest};
use foldchain::reference::{run_reference, ReferenceOptions};
use foldchain::timeline::{Outcome, TileDesigns};
use foldchain::{Chain, Design};

/// Margins closer to zero than this (0.3% of the bond force) are not compared: the
/// quasi-static poses are not the reference's trajectories, only near them.
const DECISIVE: f64 = 0.003;

#[test]
fn margins_agree_with_the_reference_on_short_chains() {
    let (mut compared, mut stalled) = (0, 0);
    for design in [
        Design::thesis(),
        Design::thesis().with_s(0.1),
        Design::thesis().with_s(0.45),
        Design {
            wall: 1.3,
            ..Design::thesis()
        },
        Design {
            wall: 1.2,
            ..Design::thesis()
        },
        Design {
            c: Some(2.8),
            ..Design::thesis()
        },
    ] {
        for word in ["SS", "SL", "LS", "LL", "SSL", "SLS", "LLS", "RSL"] {
            let chain = Chain::parse(word).unwrap();
            let m = Margins::of(&chain, &[design], &MarginOptions::default()).unwrap();
            let weakest = m.weakest().unwrap();
            if weakest.margin().abs() < DECISIVE {
                continue;
            }
            let run = run_reference(
                &chain,
                &TileDesigns::global(design),
                &ReferenceOptions::default(),
            )
            .unwrap();
            let completed = run.outcome == Outcome::Completed;
            assert_eq!(
                m.folds_as_designed(),
                completed,
                "{word} s {} c {:?}: margins {weakest}, reference {:?}",
                design.s,
                design.c,
                run.outcome
            );
            if let (Some(Weakest::Start { magnet, .. }), Outcome::Stalled { magnet: r, .. }) =
                (m.first_failure(), &run.outcome)
            {
                assert_eq!(magnet, *r, "{word}: the stalled magnet");
            }
            compared += 1;
            stalled += usize::from(!completed);
        }
    }
    eprintln!("{compared} decisive cases compared, {stalled} of them stalled");
    assert!(
        stalled >= 5,
        "only {stalled} stalls: the comparison must see both verdicts"
    );
    assert!(compared >= 30, "only {compared} decisive cases");
}

#[test]
fn a_stalled_mover_stops_where_the_reference_stops() {
    // the reference stalls word SL's magnet 3 where the forces along its path balance; the
    // margins find the same balance on their quasi-static pose when it is the stall
    let chain = Chain::parse("SL").unwrap();
    let design = Design {
        c: Some(2.8),
        ..Design::thesis()
    };
    let m = Margins::of(&chain, &[design], &MarginOptions::default()).unwrap();
    let run = run_reference(
        &chain,
        &TileDesigns::global(design),
        &ReferenceOptions::default(),
    )
    .unwrap();
    let stall = m.starts[4].mover_stall.unwrap();
    assert!(matches!(run.outcome, Outcome::Stalled { magnet: 4, .. }));
    let var = run.model.magnet_var(3);
    let reference = run.final_state[var] * run.model.path_length(3);
    assert!(
        (stall - reference).abs() < 1e-3,
        "margins {stall} mm, reference {reference} mm"
    );
    assert!(m.starts[4].margin < 0.0);
}

#[test]
fn every_tile_may_differ() {
    let chain = Chain::parse("SSLLSS").unwrap();
    let d = Design::thesis();
    let mut designs = vec![d; chain.len()];
    designs[3].remanence *= 1.02;
    designs[4].tile_width += 0.1;
    let m = Margins::of(&chain, &designs, &MarginOptions::default()).unwrap();
    let uniform = Margins::of(&chain, &[d], &MarginOptions::default()).unwrap();
    // tiles far from the change keep their margins; tiles next to it do not
    assert_eq!(m.starts[0], uniform.starts[0]);
    assert_ne!(m.starts[7], uniform.starts[7]);
    let e = Margins::of(&chain, &designs[..3], &MarginOptions::default()).unwrap_err();
    assert!(e.to_string().contains("3 tile designs"), "{e}");
    designs[2].remanence = -1.0;
    let e = Margins::of(&chain, &designs, &MarginOptions::default()).unwrap_err();
    assert!(e.to_string().starts_with("tile 2:"), "{e}");
}

/// The largest `x` in `[lo, hi]` at which `f` is positive, by bisection (f(lo) > 0 >= f(hi)).
fn edge(f: impl Fn(f64) -> f64, lo: f64, hi: f64) -> f64 {
    assert!(
        f(lo) > 0.0 && f(hi) <= 0.0,
        "no sign change in [{lo}, {hi}]"
    );
    let (mut a, mut b) = (lo, hi);
    for _ in 0..30 {
        let m = 0.5 * (a + b);
        if f(m) > 0.0 {
            a = m;
        } else {
            b = m;
        }
    }
    a
}

#[test]
fn the_margins_edge_is_the_references_edge() {
    // the wall (and s) at which the last fold of SL and LS stops starting, found on the
    // margins alone; the reference completes just inside it and stalls just outside
    let smallest = |word: &str, d: Design| {
        let chain = Chain::parse(word).unwrap();
        Margins::of(&chain, &[d], &MarginOptions::default())
            .unwrap()
            .weakest()
            .unwrap()
            .margin()
    };
    let completes = |word: &str, d: Design| {
        let run = run_reference(
            &Chain::parse(word).unwrap(),
            &TileDesigns::global(d),
            &ReferenceOptions::default(),
        )
        .unwrap();
        run.outcome == Outcome::Completed
    };
    let d = Design::thesis();
    for word in ["SL", "LS"] {
        let wall = edge(|w| smallest(word, Design { wall: w, ..d }), 0.5, 2.5);
        assert!(
            completes(
                word,
                Design {
                    wall: wall - 0.003,
                    ..d
                }
            ),
            "{word} wall {wall}"
        );
        assert!(
            !completes(
                word,
                Design {
                    wall: wall + 0.003,
                    ..d
                }
            ),
            "{word} wall {wall}"
        );
        let s = edge(|s| smallest(word, d.with_s(s)), 0.2, 1.0);
        assert!(completes(word, d.with_s(s - 0.003)), "{word} s {s}");
        assert!(!completes(word, d.with_s(s + 0.003)), "{word} s {s}");
    }
}
