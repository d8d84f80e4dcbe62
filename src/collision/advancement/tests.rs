//! Tests of the timed schedule check: against exact sweeps, a plain pairwise advancement
//! on random schedules, and the check cut into pieces.

use std::f64::consts::FRAC_PI_2;

use super::*;
use crate::collision::JointTrack;

fn word(s: &str) -> FoldWord {
    FoldWord::parse(s).unwrap()
}

/// Every joint folding at once, linearly over one second.
fn simultaneous(w: &FoldWord) -> FoldSchedule {
    FoldSchedule {
        tracks: w
            .folds()
            .iter()
            .enumerate()
            .filter(|(_, f)| f.quarter_turns() != 0)
            .map(|(joint, f)| JointTrack {
                joint,
                times: vec![0.0, 1.0],
                angles: vec![0.0, f.quarter_turns() as f64 * FRAC_PI_2],
                ended: None,
            })
            .collect(),
    }
}

#[test]
fn sequential_schedule_uses_exact_check_and_reports_time() {
    let w = word("LLLL");
    let e = check_schedule(
        &w,
        &FoldSchedule::sequential(&w, 2.0),
        &CheckOptions::default(),
    )
    .unwrap_err();
    let ScheduleError::Collision(c) = e else {
        panic!("{e}")
    };
    assert_eq!(c.joint, Some(2));
    let t = c.time.unwrap();
    assert!(t > 4.0 && t < 6.0, "{t}"); // joint 2 folds from t = 4 s to 6 s
    assert!(check_schedule(
        &word("LLL"),
        &FoldSchedule::sequential(&word("LLL"), 1.0),
        &CheckOptions::default()
    )
    .is_ok());
}

#[test]
fn simultaneous_ring_closes_touching() {
    let w = word("LLL");
    assert!(check_schedule(&w, &simultaneous(&w), &CheckOptions::default()).is_ok());
}

#[test]
fn simultaneous_five_in_a_ring_collides_before_the_end() {
    let w = word("LLLL");
    match check_schedule(&w, &simultaneous(&w), &CheckOptions::default()) {
        Err(ScheduleError::Collision(c)) => {
            assert_eq!(c.tiles, (0, 4));
            let t = c.time.unwrap();
            assert!(t > 0.0 && t < 1.0, "{t}");
        }
        other => panic!("{other:?}"),
    }
}

#[test]
fn a_contact_names_the_fold_front_not_the_fastest_joint() {
    // the ring LLLL folding at once, joint 3 (the front) three times slower than the
    // others: tiles 0 and 4 meet while all four turn, joints 0 to 2 the fastest
    let w = word("LLLL");
    let mut s = simultaneous(&w);
    s.tracks[3].times[1] = 3.0;
    match check_schedule(&w, &s, &CheckOptions::default()) {
        Err(ScheduleError::Collision(c)) => {
            assert_eq!(c.tiles, (0, 4));
            let t = c.time.unwrap();
            assert!(t > 0.0 && t < 1.0, "{t}: joints 0 to 2 still turn");
            assert_eq!(c.joint, Some(3));
            assert!((c.angle_deg - 30.0 * t).abs() < 1e-6, "{c:?}");
        }
        other => panic!("{other:?}"),
    }
    // joint 2 the front once joint 3 has closed: LLLL with joint 3 done first
    let mut s = simultaneous(&w);
    s.tracks[3].times = vec![0.0, 0.1];
    if let Err(ScheduleError::Collision(c)) = check_schedule(&w, &s, &CheckOptions::default()) {
        assert!(c.time.unwrap() > 0.1);
        assert_eq!(c.joint, Some(2), "{c:?}");
    } else {
        panic!("LLLL collides");
    }
}

#[test]
fn general_advancement_agrees_with_exact_sweeps() {
    // the same sequential folding, but with a pause in each track so that it is not
    // recognised as sequential: both methods must agree on every word of 5 and 6 tiles.
    for n in [5usize, 6] {
        let mut letters = vec![crate::Fold::S; n - 1];
        let total = 3usize.pow((n - 1) as u32);
        for code in 0..total {
            let mut c = code;
            for l in letters.iter_mut() {
                *l = crate::Fold::ALL[c % 3];
                c /= 3;
            }
            let w = FoldWord::from_folds(letters.clone());
            let exact = check_word(&w, &CheckOptions::default()).is_ok();
            let mut s = FoldSchedule::sequential(&w, 1.0);
            for tr in &mut s.tracks {
                // overlap each fold slightly with the next: not sequential any more
                tr.times[1] += 0.02;
            }
            let general = match check_schedule(&w, &s, &CheckOptions::default()) {
                Ok(()) => true,
                Err(ScheduleError::Collision(_)) => false,
                Err(e) => panic!("{w}: {e}"),
            };
            assert_eq!(exact, general, "word {w}");
        }
    }
}

#[test]
fn bad_tracks_are_refused_before_any_check() {
    let s = FoldSchedule {
        tracks: vec![JointTrack::open(5, &[0.0], &[0.0])],
    };
    assert!(matches!(
        check_schedule(&word("SL"), &s, &CheckOptions::default()),
        Err(ScheduleError::BadTrack { joint: 5, .. })
    ));
}

/// The plain check the block check must agree with: every pair of tiles with a moving
/// joint between them, conservative advancement with one global step (each tile's speed
/// bounded by its chain distance from the moving hinges), poses from the kinematics.
/// `None` when clean; the contact time and tiles otherwise; panics past `max_steps`.
fn plain_check(w: &FoldWord, s: &FoldSchedule, max_steps: usize) -> Option<(f64, (usize, usize))> {
    use crate::{kinematics, Pose};
    let n = w.tiles();
    let shape = Octagon::new(1.0)
        .to_parry(CheckOptions::default().tolerance)
        .unwrap();
    let r = Octagon::new(1.0).circumradius();
    // consecutive centres are at most two hinge distances apart
    let step = 2.0 * (0.25 + 0.25 * (std::f64::consts::SQRT_2 - 1.0).powi(2)).sqrt();
    let walk = Walk::new(w, s);
    let mut steps = 0;
    for seg in walk.breakpoints.windows(2) {
        let (ta, tb) = (seg[0], seg[1]);
        let (a0, a1) = (s.angles_at(w.joints(), ta), s.angles_at(w.joints(), tb));
        let rate: Vec<f64> = (0..w.joints())
            .map(|k| ((a1[k] - a0[k]) / (tb - ta)).abs())
            .collect();
        let bound = |i: usize, j: usize| -> f64 {
            (i..j).map(|k| rate[k] * (step * (j - k) as f64 + r)).sum()
        };
        let mut t = ta;
        while t < tb {
            let poses: Vec<Pose> = kinematics::poses_at_angles(&s.angles_at(w.joints(), t), 1.0);
            let mut dt = tb - t;
            for j in 0..n {
                for i in 0..j.saturating_sub(1) {
                    let v = bound(i, j);
                    if v == 0.0 {
                        continue;
                    }
                    let d = parry2d_f64::query::distance(
                        &poses[i].to_parry(),
                        &shape,
                        &poses[j].to_parry(),
                        &shape,
                    )
                    .unwrap();
                    if d <= 1e-12 {
                        return Some((t, (i, j)));
                    }
                    dt = dt.min(d / v);
                }
            }
            steps += 1;
            assert!(steps < max_steps, "plain check did not finish");
            t += dt.max(1e-13);
        }
    }
    None
}

/// A random word of `tiles.0 + [0, tiles.1)` tiles, each letter straight with
/// probability `straight` (else L or R), and a random overlapping schedule: folding
/// joints through `knots` random angles on the way, some straight joints wiggling
/// through straight (changing hinge).
pub(super) fn random_case(
    next: &mut impl FnMut() -> f64,
    tiles: (usize, usize),
    straight: f64,
    knots: usize,
) -> (FoldWord, FoldSchedule) {
    let n = tiles.0 + (next() * tiles.1 as f64) as usize;
    let folds: Vec<crate::Fold> = (0..n - 1)
        .map(|_| {
            if next() < straight {
                crate::Fold::S
            } else {
                crate::Fold::ALL[1 + (next() * 2.0) as usize % 2]
            }
        })
        .collect();
    let w = FoldWord::from_folds(folds);
    let mut tracks = Vec::new();
    for (joint, f) in w.folds().iter().enumerate() {
        let start = next() * n as f64 * 0.4;
        let len = 0.3 + next();
        let target = f.quarter_turns() as f64 * FRAC_PI_2;
        if target != 0.0 {
            let mut times: Vec<f64> = (0..knots).map(|_| start + len * next()).collect();
            times.sort_by(f64::total_cmp);
            let mut angles: Vec<f64> = (0..knots).map(|_| target * (0.2 + 0.8 * next())).collect();
            times.insert(0, start);
            angles.insert(0, 0.0);
            times.push(start + len);
            angles.push(target);
            tracks.push(JointTrack {
                joint,
                times,
                angles,
                ended: None,
            });
        } else if next() < 0.3 {
            let a = 0.4 * (next() - 0.5);
            tracks.push(JointTrack {
                joint,
                times: vec![start, start + 0.5 * len, start + len],
                angles: vec![0.0, a, -a],
                ended: None,
            });
        }
    }
    (w, FoldSchedule { tracks })
}

/// Random words and random overlapping schedules (folding joints through `knots` random
/// angles on the way, some straight joints wiggling through straight, changing hinge),
/// checked by the block check and by the plain check: the same verdict, the same tiles
/// and contact time. `rounds` words of `tiles.0 + [0, tiles.1)` tiles, each letter
/// straight with probability `straight` (else L or R). Returns (collided, clean).
fn agrees_with_the_plain_check(
    seed: u64,
    rounds: usize,
    tiles: (usize, usize),
    straight: f64,
    knots: usize,
) -> (usize, usize) {
    let mut bits = super::super::xorshift(seed);
    let mut next = move || (bits() >> 11) as f64 / (1u64 << 53) as f64;
    let (mut collided, mut clean) = (0, 0);
    for round in 0..rounds {
        let (w, s) = random_case(&mut next, tiles, straight, knots);
        let fast = match check_schedule(&w, &s, &CheckOptions::default()) {
            Ok(()) => None,
            Err(ScheduleError::Collision(c)) => Some((c.time.unwrap(), c.tiles)),
            Err(e) => panic!("round {round}: {e}"),
        };
        let plain = plain_check(&w, &s, 2_000_000);
        match (fast, plain) {
            (None, None) => clean += 1,
            (Some((t, ti)), Some((tp, tip))) => {
                assert_eq!(ti, tip, "round {round} {w}");
                assert!(
                    (t - tp).abs() < 1e-6 * (1.0 + tp.abs()),
                    "round {round} {w}: {t} {tp}"
                );
                collided += 1;
            }
            _ => panic!("round {round} {w}: {fast:?} against {plain:?}"),
        }
    }
    (collided, clean)
}

#[test]
fn block_check_agrees_with_the_plain_check() {
    // short words, one knot in each fold
    let (collided, clean) =
        agrees_with_the_plain_check(0x5DEE_CE66_D1CE_B00F, 300, (4, 7), 1.0 / 3.0, 1);
    assert!(collided > 40 && clean > 150, "{collided} {clean}");
}

#[test]
fn block_check_agrees_on_long_rows_and_many_knots() {
    // longer words, mostly straight (rows whose boxes the check steps on), folds with
    // many knots (pairs of blocks carried past segments' ends)
    let (collided, clean) =
        agrees_with_the_plain_check(0x0DDB_A11C_0FFE_E124, 150, (15, 20), 0.8, 8);
    assert!(collided > 25 && clean > 50, "{collided} {clean}");
}

#[test]
fn pieces_give_the_verdict_of_one_walk() {
    // the same random schedules walked in one piece and cut into 2, 3 and 7 pieces
    // (each starting afresh, without the pairs carried in): the same verdict, tiles,
    // joint and contact time
    let mut bits = super::super::xorshift(0x9E37_79B9_7F4A_7C15);
    let mut next = move || (bits() >> 11) as f64 / (1u64 << 53) as f64;
    let shape = Octagon::new(1.0).to_parry(1e-7).unwrap();
    let (mut collided, mut clean) = (0, 0);
    for round in 0..120 {
        let (w, s) = random_case(&mut next, (12, 20), 0.7, 6);
        let mut tracks = s.clone();
        tracks.tracks.sort_by_key(|t| t.joint);
        let walk = Walk::new(&w, &tracks);
        let one = walk.run_in(&shape, 1e-7, 1);
        for pieces in [2, 3, 7] {
            let cut = walk.run_in(&shape, 1e-7, pieces);
            match (&one, &cut) {
                (Ok(()), Ok(())) => {}
                (Err(ScheduleError::Collision(a)), Err(ScheduleError::Collision(b))) => {
                    assert_eq!((a.tiles, a.joint), (b.tiles, b.joint), "round {round}");
                    let (ta, tb) = (a.time.unwrap(), b.time.unwrap());
                    assert!((ta - tb).abs() <= 1e-9 * (1.0 + ta), "round {round}");
                }
                _ => panic!("round {round} {w} in {pieces}: {one:?} against {cut:?}"),
            }
        }
        match one {
            Ok(()) => clean += 1,
            Err(_) => collided += 1,
        }
    }
    assert!(collided > 20 && clean > 20, "{collided} {clean}");
}
