//! Speed against accuracy, measured: a work-precision study of every applicable method on six
//! scenes, each against its own reference.
//!
//! `cargo run --release --example tradeoff` writes, under `out/tradeoff/`, for each scene
//! (`spring`, `kepler`, `lorenz`, `arenstorf`, `pleiades`, `robertson`): `<scene>.csv`
//! (`scene,method,dt,steps,error,energy_error,seconds,evaluations`), `<scene>.png` (error against
//! wall time; for Kepler the energy error, since over 1000 orbits the final state's error is
//! phase error; `<scene>.svg` is the same chart, where each point shows its dt or rtol on
//! hover) and `<scene>_evaluations.png` (against evaluations); and
//! `kepler_invariants.csv` (`method,dt,orbits,energy_error,angular_momentum_error`).
//! `--quick` runs fewer steps and a single timing repeat.

#![allow(
    clippy::excessive_precision,
    reason = "references keep the digits they were computed with"
)]

use std::path::Path;
use std::process::ExitCode;

use odyn::output::{number, write_table};
use odyn::prelude::*;
use odyn::reference::{DampedOscillator, KeplerOrbit};
use odyn::work_precision::{Accuracy, Cost, Reference, WorkPrecision, WorkPrecisionSet, measure};
// The six scenes, each written once for the examples, tests and benches (`scenes/src/`).
use scenes::{
    Arenstorf, Kepler, KeplerState, Lorenz, Pleiades, Robertson, RobertsonState, Spring,
    SpringState,
};

/// Speed against accuracy, measured: a work-precision study of every applicable method on six
/// scenes, each against its own reference.
///
/// Writes its CSV files and charts under `out/tradeoff/` (the example's source says what each
/// holds).
#[derive(clap::Parser)]
struct Cli {
    /// Fewer steps and tolerances, shorter horizons and one timing repeat instead of three
    #[arg(long)]
    quick: bool,
}

fn main() -> ExitCode {
    let cli = <Cli as clap::Parser>::parse();
    match run(cli.quick) {
        Ok(()) => ExitCode::SUCCESS,
        Err(error) => {
            eprintln!("error: {error}");
            ExitCode::FAILURE
        }
    }
}

fn run(quick: bool) -> odyn::Result<()> {
    let dir = Path::new("out/tradeoff");
    let halvings = |start: f64, n: usize| -> Vec<f64> {
        (0..n).map(|i| start / 2f64.powi(i as i32)).collect()
    };
    let repeats = if quick { 1 } else { 3 };

    // Damped spring, k = 50, b = 0.5, m = 1, to t = 10, against the closed form.
    let spring = Spring {
        x: 1.0,
        v: 0.0,
        k: 50.0,
        b: 0.5,
        m: 1.0,
    };
    let exact = DampedOscillator {
        k: 50.0,
        b: 0.5,
        m: 1.0,
    };
    let mut study = WorkPrecision::new(
        "spring",
        spring.state(),
        10.0,
        Reference::Exact(Box::new(move |t| {
            let (x, v) = exact.state_at(1.0, 0.0, t);
            SpringState { x, v }
        })),
    );
    study.methods = vec![
        Method::ExplicitEuler,
        Method::SymplecticEuler,
        Method::VelocityVerlet,
        Method::Leapfrog,
        Method::Rk4,
        Method::ImplicitEuler,
        Method::Tsit5,
        Method::Dop853,
    ];
    study.dts = halvings(0.016, if quick { 3 } else { 6 });
    study.tolerances = rtols(quick);
    study.repeats = repeats;
    report(&measure(&spring, &study)?, dir, Accuracy::FinalState)?;

    // Kepler, GM = 1, e = 0.5, from pericentre, over 1000 orbits, against Kepler's equation.
    let orbit = KeplerOrbit {
        gm: 1.0,
        a: 1.0,
        e: 0.5,
    };
    let kepler = Kepler {
        r: Vector2::new(0.5, 0.0),
        v: Vector2::new(0.0, 3f64.sqrt()),
        gm: 1.0,
    };
    let orbits = if quick { 100.0 } else { 1000.0 };
    let exact_kepler = move |t: f64| {
        let ([x, y], [vx, vy]) = orbit.state_at(t);
        KeplerState {
            r: Vector2::new(x, y),
            v: Vector2::new(vx, vy),
        }
    };
    let mut study = WorkPrecision::new(
        "kepler",
        kepler.state(),
        orbits * orbit.period(),
        Reference::Exact(Box::new(exact_kepler)),
    );
    study.methods = vec![
        Method::SymplecticEuler,
        Method::PositionVerlet,
        Method::VelocityVerlet,
        Method::Leapfrog,
        Method::Yoshida4,
        Method::Yoshida6,
        Method::KahanLi6,
        Method::Rk4,
        Method::ImplicitEuler,
        Method::Tsit5,
        Method::Dop853,
    ];
    study.dts = halvings(0.02, if quick { 2 } else { 4 });
    study.tolerances = rtols(quick);
    study.repeats = repeats;
    report(&measure(&kepler, &study)?, dir, Accuracy::Energy)?;
    kepler_invariants(&kepler, orbit, orbits, dir)?;

    // Lorenz at t = 1 from (1, 1, 1), against RK4 at dt = 1e-5 (its error estimated at 5e-6).
    let lorenz = Lorenz {
        x: 1.0,
        y: 1.0,
        z: 1.0,
        sigma: 10.0,
        rho: 28.0,
        beta: 8.0 / 3.0,
    };
    let mut study = WorkPrecision::new(
        "lorenz",
        lorenz.state(),
        1.0,
        Reference::Computed {
            method: Method::Rk4,
            dt: 1e-5,
        },
    );
    study.methods = vec![
        Method::ExplicitEuler,
        Method::Rk4,
        Method::ImplicitEuler,
        Method::Tsit5,
        Method::Dop853,
    ];
    study.dts = halvings(0.01, if quick { 3 } else { 6 });
    study.tolerances = rtols(quick);
    study.repeats = repeats;
    report(&measure(&lorenz, &study)?, dir, Accuracy::FinalState)?;

    // The Arenstorf orbit over one period, against its 50-digit Taylor reference
    // (scripts/reference_adaptive.py).
    let arenstorf = Arenstorf::orbit();
    let period = Arenstorf::PERIOD;
    let mut study = WorkPrecision::new(
        "arenstorf",
        arenstorf.state(),
        period,
        Reference::Final(Arenstorf::AT_PERIOD.to_vec()),
    );
    study.methods = vec![Method::Rk4, Method::Tsit5, Method::Dop853];
    study.dts = (0..if quick { 3 } else { 5 })
        .map(|i| period / (16000.0 * 2f64.powi(i)))
        .collect();
    study.tolerances = rtols(quick);
    study.repeats = repeats;
    report(&measure(&arenstorf, &study)?, dir, Accuracy::FinalState)?;

    // The Pleiades to t = 3, against their 44-digit Taylor reference
    // (scripts/reference_adaptive.py).
    let pleiades = Pleiades::start();
    let mut study = WorkPrecision::new(
        "pleiades",
        pleiades.state(),
        3.0,
        Reference::Final(Pleiades::AT_3.to_vec()),
    );
    study.methods = vec![
        Method::VelocityVerlet,
        Method::Leapfrog,
        Method::Rk4,
        Method::Tsit5,
        Method::Dop853,
    ];
    study.dts = halvings(1e-3, if quick { 3 } else { 5 });
    study.tolerances = rtols(quick);
    study.repeats = repeats;
    report(&measure(&pleiades, &study)?, dir, Accuracy::FinalState)?;

    // Robertson at t = 40 against SciPy Radau (scripts/reference.py).
    let robertson = Robertson::classic();
    let mut study = WorkPrecision::new(
        "robertson",
        robertson.state(),
        40.0,
        Reference::Final(vec![
            7.158270687199023e-01,
            9.185534764554085e-06,
            2.841637457453337e-01,
        ]),
    );
    study.methods = vec![
        Method::ImplicitEuler,
        Method::Rk4,
        Method::Rosenbrock23,
        Method::Rodas5P,
    ];
    study.dts = (0..if quick { 3 } else { 5 })
        .map(|i| 0.04 / 4f64.powi(i))
        .collect();
    // atol far below y₂ ≈ 1e-5, so the tolerance governs every component.
    study.tolerances = WorkPrecision::<RobertsonState>::rtols(3..=if quick { 8 } else { 11 }, 1e-7);
    study.repeats = repeats;
    report(&measure(&robertson, &study)?, dir, Accuracy::FinalState)?;
    println!(
        "\nwrote {}/{{spring,kepler,lorenz,arenstorf,pleiades,robertson}}.{{csv,png,svg}} and \
         *_evaluations.png",
        dir.display()
    );
    Ok(())
}

/// The tolerances the adaptive methods sweep: rtol = 1e-3 … 1e-12 (1e-3 … 1e-8 with `--quick`),
/// atol = rtol/1000.
fn rtols(quick: bool) -> Vec<odyn::Tolerances> {
    WorkPrecision::<SpringState>::rtols(3..=if quick { 8 } else { 12 }, 1e-3)
}

/// Prints a study, writes its CSV and draws `accuracy` against time and against evaluations.
fn report(set: &WorkPrecisionSet, dir: &Path, accuracy: Accuracy) -> odyn::Result<()> {
    let reference = if set.reference_error == 0.0 {
        "exact".to_owned()
    } else if set.reference_error.is_nan() {
        match set.scene.as_str() {
            "robertson" => "given (SciPy Radau)".to_owned(),
            _ => "given (Taylor series, scripts/reference_adaptive.py)".to_owned(),
        }
    } else {
        format!("computed, its own error ≈ {:.1e}", set.reference_error)
    };
    println!("\n{} (reference: {reference})", set.scene);
    println!(
        "  {:<17} {:>13} {:>9} {:>11} {:>11} {:>11} {:>11}",
        "method", "dt / rtol", "steps", "error", "energy err", "seconds", "evaluations"
    );
    for m in &set.measurements {
        let energy = m
            .energy_error
            .map_or_else(|| "—".to_owned(), |e| format!("{e:.2e}"));
        let error = if m.diverged {
            "diverged".to_owned()
        } else {
            format!("{:.2e}", m.error)
        };
        let setting = match &m.stepping {
            Stepping::Fixed(dt) => format!("dt {dt:.3e}"),
            Stepping::Adaptive(t) => format!("rtol {:.0e}", t.rtol),
        };
        println!(
            "  {:<17} {setting:>13} {:>9} {error:>11} {energy:>11} {:>11.3e} {:>11}",
            m.method.name(),
            m.stats.steps,
            m.seconds,
            m.evaluations()
        );
    }
    let mut methods: Vec<Method> = set.measurements.iter().map(|m| m.method).collect();
    methods.dedup();
    let orders: Vec<String> = methods
        .iter()
        .filter_map(|&m| {
            set.observed_order(m)
                .map(|o| format!("{} {o:.2}", m.name()))
        })
        .collect();
    println!("  observed orders: {}", orders.join(", "));
    set.write_csv(dir.join(format!("{}.csv", set.scene)))?;
    for image in ["png", "svg"] {
        set.plot(
            dir.join(format!("{}.{image}", set.scene)),
            accuracy,
            Cost::Seconds,
        )?;
    }
    set.plot(
        dir.join(format!("{}_evaluations.png", set.scene)),
        accuracy,
        Cost::Evaluations,
    )
}

/// Energy and angular momentum L = x·v_y − y·v_x along each method's run at dt = 0.01: the
/// split methods conserve L to round-off (it is a quadratic invariant of a central force).
fn kepler_invariants(
    kepler: &Kepler,
    orbit: KeplerOrbit,
    orbits: f64,
    dir: &Path,
) -> odyn::Result<()> {
    println!("  invariants over {orbits} orbits at dt = 0.01 (max relative drift):");
    let mut rows = Vec::new();
    for method in [
        Method::SymplecticEuler,
        Method::VelocityVerlet,
        Method::Leapfrog,
        Method::Yoshida4,
        Method::KahanLi6,
        Method::Rk4,
        Method::ImplicitEuler,
    ] {
        let sim = kepler
            .simulate()
            .integrator(method)
            .dt(0.01)
            .duration(orbits * orbit.period())
            .record_every(10);
        let (run, failure) = sim.run_partial()?;
        if let Some(error) = failure {
            // Implicit Euler's numerical damping spirals the orbit into the singularity at r = 0.
            println!(
                "    {:<17} stopped at t = {:.1}: {error}",
                method.name(),
                run.last().t
            );
            continue;
        }
        let l = |s: &KeplerState| s.r.x * s.v.y - s.r.y * s.v.x;
        let (e0, l0) = (
            run.first().energy.unwrap_or(f64::NAN),
            l(&run.first().state),
        );
        let energy = run
            .energies()
            .map(|(_, e)| ((e - e0) / e0).abs())
            .fold(0.0, f64::max);
        let momentum = run
            .samples
            .iter()
            .map(|s| ((l(&s.state) - l0) / l0).abs())
            .fold(0.0, f64::max);
        println!(
            "    {:<17} energy {energy:.2e}  angular momentum {momentum:.2e}",
            method.name()
        );
        rows.push(vec![
            method.name().to_owned(),
            "0.01".to_owned(),
            number(orbits),
            number(energy),
            number(momentum),
        ]);
    }
    write_table(
        dir.join("kepler_invariants.csv"),
        &[
            "method",
            "dt",
            "orbits",
            "energy_error",
            "angular_momentum_error",
        ],
        &rows,
    )
}
