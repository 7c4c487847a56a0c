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
use odyn::work_precision::{
    Accuracy, Cost, Reference, Setting, WorkPrecision, WorkPrecisionSet, measure,
};

/// Damped spring, m·ẍ = −k·x − b·ẋ.
#[system]
pub struct Spring {
    /// Displacement.
    #[position]
    pub x: f64,
    /// Velocity.
    #[velocity]
    pub v: f64,
    /// Stiffness.
    pub k: f64,
    /// Damping.
    pub b: f64,
    /// Mass.
    pub m: f64,
}

#[system]
impl Spring {
    fn acceleration(&self) -> f64 {
        (-self.k * self.x - self.b * self.v) / self.m
    }

    fn energy(&self) -> f64 {
        0.5 * self.m * self.v * self.v + 0.5 * self.k * self.x * self.x
    }
}

/// The planar Kepler problem, r̈ = −GM·r/|r|³.
#[system]
pub struct Kepler {
    /// Position.
    #[position]
    pub r: Vector2<f64>,
    /// Velocity.
    #[velocity]
    pub v: Vector2<f64>,
    /// Gravitational parameter.
    pub gm: f64,
}

#[system]
impl Kepler {
    fn acceleration(&self) -> Vector2<f64> {
        let r = self.r;
        -self.gm * r / r.norm().powi(3)
    }

    fn energy(&self) -> f64 {
        0.5 * self.v.norm_squared() - self.gm / self.r.norm()
    }
}

/// The Lorenz system.
#[system]
pub struct Lorenz {
    /// x
    #[state]
    pub x: f64,
    /// y
    #[state]
    pub y: f64,
    /// z
    #[state]
    pub z: f64,
    /// σ
    pub sigma: f64,
    /// ρ
    pub rho: f64,
    /// β
    pub beta: f64,
}

#[system]
impl Lorenz {
    fn derivative(&self) -> LorenzState {
        LorenzState {
            x: self.sigma * (self.y - self.x),
            y: self.x * (self.rho - self.z) - self.y,
            z: self.x * self.y - self.beta * self.z,
        }
    }
}

/// The Arenstorf orbit: a satellite in the rotating frame of the Earth–Moon system, periodic
/// (Hairer, Nørsett & Wanner, *Solving ODEs I*, §II.0, eq. (0.1)).
#[system]
pub struct Arenstorf {
    /// First coordinate in the rotating frame.
    #[position]
    pub y1: f64,
    /// Second coordinate.
    #[position]
    pub y2: f64,
    /// y1′.
    #[velocity]
    pub v1: f64,
    /// y2′.
    #[velocity]
    pub v2: f64,
    /// The Moon's mass fraction μ.
    pub mu: f64,
}

#[system]
impl Arenstorf {
    fn acceleration(&self) -> (f64, f64) {
        let mu = self.mu;
        let mup = 1.0 - self.mu;
        let d1 = ((self.y1 + mu).powi(2) + self.y2.powi(2)).powf(1.5);
        let d2 = ((self.y1 - mup).powi(2) + self.y2.powi(2)).powf(1.5);
        (
            self.y1 + 2.0 * self.v2 - mup * (self.y1 + mu) / d1 - mu * (self.y1 - mup) / d2,
            self.y2 - 2.0 * self.v1 - mup * self.y2 / d1 - mu * self.y2 / d2,
        )
    }
}

/// The Pleiades: seven bodies in the plane under Newtonian gravity, G = 1 (HNW I, §II.10,
/// eq. (10.12); problem PLEI of the Bari test set). The loops over the bodies are outside what
/// the Jacobian generator differentiates, so explicit methods only.
#[system(jacobian = false)]
pub struct Pleiades {
    /// x coordinates.
    #[position]
    pub x: [f64; 7],
    /// y coordinates.
    #[position]
    pub y: [f64; 7],
    /// x velocities.
    #[velocity]
    pub u: [f64; 7],
    /// y velocities.
    #[velocity]
    pub v: [f64; 7],
    /// Masses.
    pub m: [f64; 7],
}

#[system]
impl Pleiades {
    fn acceleration(&self) -> ([f64; 7], [f64; 7]) {
        let mut ax = [0.0; 7];
        let mut ay = [0.0; 7];
        for i in 0..7 {
            for j in (i + 1)..7 {
                let dx = self.x[j] - self.x[i];
                let dy = self.y[j] - self.y[i];
                let r2 = dx * dx + dy * dy;
                let w = 1.0 / (r2 * r2.sqrt());
                ax[i] += self.m[j] * w * dx;
                ay[i] += self.m[j] * w * dy;
                ax[j] -= self.m[i] * w * dx;
                ay[j] -= self.m[i] * w * dy;
            }
        }
        (ax, ay)
    }
}

/// Robertson's chemical kinetics.
#[system]
pub struct Robertson {
    /// A
    #[state]
    pub a: f64,
    /// B
    #[state]
    pub b: f64,
    /// C
    #[state]
    pub c: f64,
}

#[system]
impl Robertson {
    fn derivative(&self) -> RobertsonState {
        let slow = 0.04 * self.a;
        let exchange = 1e4 * self.b * self.c;
        let fast = 3e7 * self.b * self.b;
        RobertsonState {
            a: -slow + exchange,
            b: slow - exchange - fast,
            c: fast,
        }
    }
}

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
    let arenstorf = Arenstorf {
        y1: 0.994,
        y2: 0.0,
        v1: 0.0,
        v2: -2.001_585_106_379_082_4,
        mu: 0.012_277_471,
    };
    // fl(T), T = 17.0652165601579625588917206249 (HNW I, eq. (0.2)).
    let period = 17.065_216_560_157_964;
    let mut study = WorkPrecision::new(
        "arenstorf",
        arenstorf.state(),
        period,
        Reference::Final(vec![
            9.939_999_999_999_088_5e-1,
            -3.030_943_022_982_418_5e-13,
            -4.928_536_581_055_052_6e-11,
            -2.001_585_106_393_270_1,
        ]),
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
    let pleiades = Pleiades {
        x: [3.0, 3.0, -1.0, -3.0, 2.0, -2.0, 2.0],
        y: [3.0, -3.0, 2.0, 0.0, 0.0, -4.0, 4.0],
        u: [0.0, 0.0, 0.0, 0.0, 0.0, 1.75, -1.5],
        v: [0.0, 0.0, 0.0, -1.25, 1.0, 0.0, 0.0],
        m: [1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0],
    };
    let mut study = WorkPrecision::new(
        "pleiades",
        pleiades.state(),
        3.0,
        Reference::Final(PLEIADES_AT_3.to_vec()),
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
    let robertson = Robertson {
        a: 1.0,
        b: 0.0,
        c: 0.0,
    };
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

/// The Pleiades at t = 3, Taylor series at 44 digits (scripts/reference_adaptive.py), in the
/// layout x₁…x₇, y₁…y₇, ẋ₁…ẋ₇, ẏ₁…ẏ₇.
const PLEIADES_AT_3: [f64; 28] = [
    3.706_139_143_970_512_7e-1,
    3.237_284_092_057_233_2,
    -3.222_559_032_418_323_5,
    6.597_091_455_775_308e-1,
    3.425_581_707_156_579_7e-1,
    1.562_172_101_400_631_1,
    -7.003_092_922_212_494_9e-1,
    -3.943_437_585_517_392_2,
    -3.271_380_973_972_549_9,
    5.225_081_843_456_544,
    -2.590_612_434_977_469_3,
    1.198_213_693_392_274_7,
    -2.429_682_344_935_823_5e-1,
    1.091_449_240_428_979_7,
    3.417_003_806_314_314_7,
    1.354_584_501_625_501_1,
    -2.590_065_597_810_775_6,
    2.025_053_734_714_241_2,
    -1.155_815_100_160_449_1,
    -8.072_988_170_223_022_2e-1,
    5.952_396_354_208_718_8e-1,
    -3.741_244_961_234_008_4,
    3.773_459_685_750_629_2e-1,
    9.386_858_869_551_079_1e-1,
    3.667_922_227_200_569_6e-1,
    -3.474_046_353_808_494_2e-1,
    2.344_915_448_180_937_1,
    -1.947_020_434_263_292,
];

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
        let setting = match &m.setting {
            Setting::Dt(dt) => format!("dt {dt:.3e}"),
            Setting::Tolerances(t) => format!("rtol {:.0e}", t.rtol),
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
