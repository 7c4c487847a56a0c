//! Ensembles: bit-identical on any thread count and any split into shards, typed errors for
//! shards that do not add up, reductions checked against closed forms, and Monte Carlo error
//! falling as 1/√N.

use std::f64::consts::PI;
use std::sync::atomic::{AtomicU64, Ordering};
use std::time::{Duration, Instant};

use odyn::Error;
use odyn::ensemble::{Ensemble, MemberRng, Members, Shard};
use odyn::rand::Rng;

use crate::common::in_pool;

/// π by hit-or-miss with `n` points in the unit square: 4·(hits / n).
fn pi_estimate(n: u64, rng: &mut MemberRng) -> f64 {
    let hits = (0..n)
        .filter(|_| {
            let (x, y): (f64, f64) = (rng.random(), rng.random());
            x * x + y * y <= 1.0
        })
        .count();
    4.0 * hits as f64 / n as f64
}

pub(super) fn pi_ensemble(members: u64, shard: Shard) -> Members {
    let ensemble = Ensemble {
        members,
        seed: 2026,
        shard,
        ..Ensemble::default()
    };
    ensemble
        .run(|_, rng| Ok(vec![pi_estimate(1000, rng), rng.random()]))
        .unwrap()
}

#[test]
fn results_are_bit_identical_on_any_thread_count() {
    let one = in_pool(1, || pi_ensemble(64, Shard::WHOLE));
    for threads in [2, 3, 7] {
        let many = in_pool(threads, || pi_ensemble(64, Shard::WHOLE));
        assert_eq!(one, many, "{threads} threads");
    }
    let (a, b) = (
        one.statistics().unwrap(),
        pi_ensemble(64, Shard::WHOLE).statistics().unwrap(),
    );
    assert_eq!(a.mean[0].to_bits(), b.mean[0].to_bits());
    assert_eq!(a.variance[0].to_bits(), b.variance[0].to_bits());
}

#[test]
fn shards_merge_bit_identical_to_one_run_through_files() {
    let whole = pi_ensemble(23, Shard::WHOLE);
    let dir = std::env::temp_dir().join(format!("odyn-ensemble-{}", std::process::id()));
    for count in [1, 2, 5, 23] {
        let parts: Vec<Members> = (0..count)
            .map(|index| {
                let part = pi_ensemble(23, Shard { index, count });
                let path = dir.join(format!("shard-{index}-of-{count}.csv"));
                part.write_csv(&path).unwrap();
                Members::read_csv(&path).unwrap()
            })
            .rev() // any order
            .collect();
        let merged = Members::merge(parts).unwrap();
        assert_eq!(merged, whole, "{count} shards");
        let (m, w) = (merged.statistics().unwrap(), whole.statistics().unwrap());
        assert_eq!(m, w);
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn shards_that_do_not_add_up_are_typed_errors() {
    let part = |index| pi_ensemble(10, Shard { index, count: 3 });
    // Shard 1 of 3 of 10 members is members ⌊10/3⌋ … ⌊20/3⌋ − 1 = 3 … 5.
    let missing = Members::merge(vec![part(0), part(2)]).unwrap_err();
    assert!(
        matches!(&missing, Error::BadShards { members: 10, count: 3, missing, twice, .. }
            if missing.as_slice() == std::slice::from_ref(&(1..2)) && twice.is_empty())
            && missing
                .to_string()
                .contains("shard 1/3 (members 3 … 5) is missing"),
        "{missing}"
    );
    let twice = Members::merge(vec![part(0), part(1), part(1), part(2)]).unwrap_err();
    assert!(
        matches!(&twice, Error::BadShards { missing, twice, .. }
            if missing.is_empty() && *twice == [1])
            && twice.to_string().contains("1/3 (members 3 … 5)"),
        "{twice}"
    );
    let mut other = part(1);
    other.seed += 1;
    let mixed = Members::merge(vec![part(0), other, part(2)]).unwrap_err();
    assert!(mixed.to_string().contains("different ensembles"), "{mixed}");
    assert!(part(0).statistics().is_err(), "statistics of one shard");
    for bad in ["3/3", "1", "a/2", "-1/2", "1/0"] {
        assert!(Shard::parse(bad).is_err(), "{bad}");
    }
    assert_eq!(Shard::parse(" 2/5").unwrap(), Shard { index: 2, count: 5 });
    let too_many = Ensemble {
        members: 3,
        shard: Shard { index: 0, count: 4 },
        ..Ensemble::default()
    };
    assert!(too_many.run(|_, _| Ok(vec![0.0])).is_err());
    let ragged = Ensemble::default().run(|i, _| Ok(vec![0.0; 1 + (i == 7) as usize]));
    assert!(ragged.unwrap_err().to_string().contains("member 7"));
    // The lowest-numbered failing member's error, whatever the threads did.
    let failing = Ensemble::default().run(|i, _| {
        if i % 10 == 9 {
            Err(odyn::Error::Diverged {
                method: odyn::Method::Rk4,
                step: i,
                t: 0.0,
                component: String::new(),
                value: f64::NAN,
                limit: 1.0,
            })
        } else {
            Ok(vec![0.0])
        }
    });
    assert!(
        matches!(failing, Err(odyn::Error::Diverged { step: 9, .. })),
        "{failing:?}"
    );
}

/// Members that return their own index: mean (M − 1)/2, sample variance M(M + 1)/12, median
/// (M − 1)/2, quantile q at position (M − 1)q exactly (definition 7 of Hyndman & Fan 1996).
#[test]
fn reductions_match_closed_forms() {
    let m = 101u64;
    let ensemble = Ensemble {
        members: m,
        ..Ensemble::default()
    };
    let stats = ensemble
        .run(|i, _| Ok(vec![i as f64]))
        .unwrap()
        .statistics()
        .unwrap();
    let mf = m as f64;
    assert_eq!(stats.mean[0], (mf - 1.0) / 2.0);
    assert!((stats.variance[0] - mf * (mf + 1.0) / 12.0).abs() < 1e-9);
    assert_eq!(stats.quantile(0, 0.5).unwrap(), 50.0);
    assert_eq!(stats.quantile(0, 0.05).unwrap(), 5.0);
    assert!((stats.quantile(0, 0.333).unwrap() - 33.3).abs() < 1e-12);
    assert!(stats.quantile(0, 1.5).is_err() && stats.quantile(1, 0.5).is_err());

    // One member of 101 returning NaN used to shift every quantile silently (NaN sorts last,
    // so the median read 51 here); now the quantiles are NaN, like the mean (NumPy's rule).
    let stats = ensemble
        .run(|i, _| Ok(vec![if i == 7 { f64::NAN } else { i as f64 }]))
        .unwrap()
        .statistics()
        .unwrap();
    assert!(stats.mean[0].is_nan());
    for q in [0.0, 0.5, 1.0] {
        assert!(stats.quantile(0, q).unwrap().is_nan(), "q = {q}");
    }
}

/// Hit-or-miss π: each point lands in the quarter disc with probability p = π/4, so the estimate
/// 4·hits/N has standard deviation exactly 4·√(p(1 − p)/N) = √(π(4 − π)/N). Over 400 members the
/// measured RMS error at N = 10⁴ must lie within 10 % of it (the relative standard error of an
/// RMS over 400 samples is ≈ 1/√(2·400) = 3.5 %, so 10 % is ~3σ), and the mean within 4σ/√400.
#[test]
fn monte_carlo_pi_error_is_sqrt_pi_4_minus_pi_over_n() {
    let n = 10_000;
    let ensemble = Ensemble {
        members: 400,
        seed: 7,
        ..Ensemble::default()
    };
    let members = ensemble
        .run(|_, rng| Ok(vec![pi_estimate(n, rng)]))
        .unwrap();
    let rms = (members
        .rows
        .iter()
        .map(|(_, v)| (v[0] - PI).powi(2))
        .sum::<f64>()
        / 400.0)
        .sqrt();
    let theory = (PI * (4.0 - PI) / n as f64).sqrt();
    assert!(
        (rms / theory - 1.0).abs() < 0.10,
        "rms {rms:e}, theory {theory:e}"
    );
    let mean = members.statistics().unwrap().mean[0];
    assert!((mean - PI).abs() < 4.0 * theory / 20.0, "mean {mean}");
}

/// The RMS error over 400 members at N = 10², 10³, 10⁴ falls with a fitted log-log slope of
/// −½ ± 0.05 (the exact law above).
#[test]
fn monte_carlo_error_falls_as_one_over_sqrt_n() {
    let sizes = [100u64, 1000, 10_000];
    let ensemble = Ensemble {
        members: 400,
        seed: 11,
        ..Ensemble::default()
    };
    let members = ensemble
        .run(|_, rng| Ok(sizes.iter().map(|&n| pi_estimate(n, rng)).collect()))
        .unwrap();
    let points: Vec<(f64, f64)> = sizes
        .iter()
        .enumerate()
        .map(|(k, &n)| {
            let mean_square = members
                .rows
                .iter()
                .map(|(_, v)| (v[k] - PI).powi(2))
                .sum::<f64>()
                / 400.0;
            ((n as f64).ln(), 0.5 * mean_square.ln())
        })
        .collect();
    let (mx, my) = (
        points.iter().map(|p| p.0).sum::<f64>() / 3.0,
        points.iter().map(|p| p.1).sum::<f64>() / 3.0,
    );
    let slope = points.iter().map(|(x, y)| (x - mx) * (y - my)).sum::<f64>()
        / points.iter().map(|(x, _)| (x - mx) * (x - mx)).sum::<f64>();
    assert!((slope + 0.5).abs() <= 0.05, "slope {slope}");
}

// ----- bad input ---------------------------------------------------------------------------

/// A directory of its own per test (tests run in parallel in one process).
pub(super) fn scratch(test: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("odyn-ensemble-{}-{test}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// A shard whose index is not below its count used to take members past the last
/// (`Shard { index: 5, count: 2 }.range(10)` was 25..30), and a count of 0 divided by zero.
#[test]
fn a_shard_outside_its_count_is_a_typed_error() {
    for (index, count) in [(5, 2), (2, 2), (0, 0)] {
        let shard = Shard { index, count };
        let error = shard.range(10).unwrap_err();
        assert!(
            matches!(&error, Error::InvalidInput { field, .. } if field == "shard")
                && error
                    .to_string()
                    .contains(&format!("{index}/{count} does not exist")),
            "{error}"
        );
        let run = Ensemble {
            members: 10,
            shard,
            ..Ensemble::default()
        }
        .run(|_, _| Ok(vec![0.0]));
        assert!(matches!(run, Err(Error::InvalidInput { .. })), "{run:?}");
    }
    assert_eq!(Shard { index: 1, count: 3 }.range(10).unwrap(), 3..6);
    assert_eq!(Shard { index: 3, count: 4 }.range(3).unwrap(), 2..3);
    assert_eq!(Shard::WHOLE.range(10).unwrap(), 0..10);
}

/// `Members` has public fields: rows of different lengths used to panic in `statistics` (index
/// out of bounds), and a member listed twice was counted twice in the mean.
#[test]
fn members_edited_into_an_inconsistent_state_are_a_typed_error() {
    let edited = |edit: &dyn Fn(&mut Members)| {
        let mut members = pi_ensemble(4, Shard::WHOLE);
        edit(&mut members);
        members
    };
    let ragged = edited(&|m| {
        m.rows[2].1.pop();
    });
    let twice = edited(&|m| m.rows[1].0 = 0);
    let beyond = edited(&|m| m.rows[3].0 = 9);
    for (members, expected) in [
        (
            &ragged,
            "member 2 has 1 observation, member 0 has 2 observations",
        ),
        (&twice, "member 0 comes after member 0"),
        (&beyond, "member 9 is past the last of 4 members"),
    ] {
        let error = members.statistics().unwrap_err();
        assert!(
            matches!(&error, Error::InvalidInput { field, .. } if field == "members")
                && error.to_string().contains(expected),
            "{error}"
        );
    }
    // Nor are they written: the file could not be read back.
    let path = scratch("edited").join("ragged.csv");
    assert!(ragged.write_csv(&path).is_err());
    assert!(!path.exists());
}

/// 2⁴⁰ members used to allocate 79 TB for their results before the first ran (an abort), and
/// u64::MAX members overflowed the capacity (a panic). The error comes back at once: the system
/// refuses the reservation (or it overflows) before any member runs.
#[test]
fn an_ensemble_too_big_to_hold_is_a_typed_error_before_any_member_runs() {
    let ran = AtomicU64::new(0);
    // The slots alone: 104 bytes a member on 64-bit targets (114 TB), more than any machine.
    for (members, needs) in [
        (1 << 40, "1.1e12 members need 1"),
        (u64::MAX, "1.8e19 members"),
    ] {
        let ensemble = Ensemble {
            members,
            ..Ensemble::default()
        };
        let start = Instant::now();
        let error = ensemble
            .run(|_, _| {
                ran.fetch_add(1, Ordering::Relaxed);
                Ok(vec![0.0])
            })
            .unwrap_err();
        assert!(start.elapsed() < Duration::from_secs(5));
        assert!(
            matches!(&error, Error::InvalidInput { field, .. } if field == "members")
                && error.to_string().contains(needs)
                && error.to_string().contains("cannot be allocated"),
            "{error}"
        );
    }
    assert_eq!(ran.load(Ordering::Relaxed), 0);
}

/// Reading a shard file that is missing or cut short said "cannot write CSV"; a value that is
/// not a number named only its row.
#[test]
fn an_unreadable_shard_file_says_what_is_wrong_with_it() {
    let dir = scratch("unreadable");
    let missing = Members::read_csv(dir.join("missing.csv")).unwrap_err();
    assert!(
        matches!(missing, Error::Read { .. }) && missing.to_string().starts_with("cannot read"),
        "{missing}"
    );

    let path = dir.join("shard.csv");
    pi_ensemble(4, Shard::WHOLE).write_csv(&path).unwrap();
    let text = std::fs::read_to_string(&path).unwrap();
    // Cut in the last row, as a copy interrupted part-way leaves it.
    std::fs::write(&path, &text[..text.len() - 30]).unwrap();
    let truncated = Members::read_csv(&path).unwrap_err().to_string();
    assert!(
        truncated.contains("row 5")
            && truncated.contains("truncated")
            && !truncated.contains("write"),
        "{truncated}"
    );

    let mut lines: Vec<String> = text.lines().map(str::to_owned).collect();
    lines[1] = "0,4,2026,0,1,3.1,abc".to_owned();
    std::fs::write(&path, lines.join("\n") + "\n").unwrap();
    let nan = Members::read_csv(&path).unwrap_err().to_string();
    assert!(
        nan.contains("row 2") && nan.contains("column `y1`") && nan.contains("`abc`"),
        "{nan}"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Merging with an empty `Members` (no members, no rows) said "shards of different ensembles:
/// 4 members with seed 1 and 0 members with seed 0".
#[test]
fn merging_an_empty_shard_says_it_is_empty() {
    let empty = Members {
        members: 0,
        seed: 0,
        shard: Shard::WHOLE,
        rows: Vec::new(),
    };
    for parts in [
        vec![pi_ensemble(4, Shard::WHOLE), empty.clone()],
        vec![empty.clone(), pi_ensemble(4, Shard::WHOLE)],
    ] {
        let error = Members::merge(parts).unwrap_err().to_string();
        assert!(
            error.contains("empty") && !error.contains("different ensembles"),
            "{error}"
        );
    }
}
