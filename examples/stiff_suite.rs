//! Three problems of the Bari stiff test set (Mazzia & Magherini, *Test Set for Initial Value
//! Problem Solvers*, release 2.4, 2008), each solved by the Rosenbrock methods over a sweep of
//! tolerances and by implicit Euler over a sweep of steps, against a reference final state:
//!
//! - `robertson`: Robertson's kinetics to t = 1e5 (reference: the 36-digit Radau IIA run of
//!   `scripts/reference_stiff.py`, which agrees with the test set's value to 2e-14), and
//!   `robertson_1e11` to t = 1e11 (the test set's reference), Rosenbrock methods only;
//! - `hires`: the 8-species HIRES photomorphogenesis model to t = 321.8122 (the test set's
//!   reference);
//! - `van_der_pol`: van der Pol with μ = 1000 to t = 2000 (problem VDPOLM; the test set's
//!   reference).
//!
//! `cargo run --release --example stiff_suite` writes under `out/stiff_suite/`, per problem,
//! `<problem>.csv` (one row per run: method, dt or rtol, steps, rejected, error, time, the
//! evaluations, factorizations and solves), `<problem>.png` (work-precision: max-norm error of
//! the final state against wall time, log-log; lower left is better) and
//! `<problem>_evaluations.png` (against f, J and ∂f/∂t evaluations).

use std::path::Path;

use odyn::prelude::*;
use odyn::work_precision::{Accuracy, Cost, Reference, WorkPrecision, WorkPrecisionSet, measure};

/// A → B (0.04), B + C → A + C (10⁴), 2B → B + C (3·10⁷) (Robertson 1966).
#[system]
pub struct Robertson {
    /// Concentration of A.
    #[state]
    pub a: f64,
    /// Concentration of B.
    #[state]
    pub b: f64,
    /// Concentration of C.
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

/// HIRES (Schäfer 1975; Hairer & Wanner, *Solving ODEs II*, §IV.10), as in the test set's
/// `hires.f`.
#[system]
pub struct Hires {
    /// The eight concentrations.
    #[state]
    pub y: [f64; 8],
}

#[system]
impl Hires {
    fn derivative(&self) -> HiresState {
        let y = self.y;
        let bind = 280.0 * y[5] * y[7];
        HiresState {
            y: [
                -1.71 * y[0] + 0.43 * y[1] + 8.32 * y[2] + 0.0007,
                1.71 * y[0] - 8.75 * y[1],
                -10.03 * y[2] + 0.43 * y[3] + 0.035 * y[4],
                8.32 * y[1] + 1.71 * y[2] - 1.12 * y[3],
                -1.745 * y[4] + 0.43 * y[5] + 0.43 * y[6],
                -bind + 0.69 * y[3] + 1.71 * y[4] - 0.43 * y[5] + 0.69 * y[6],
                bind - 1.81 * y[6],
                -bind + 1.81 * y[6],
            ],
        }
    }
}

/// van der Pol's oscillator, y₁′ = y₂, y₂′ = μ(1 − y₁²)y₂ − y₁.
#[system]
pub struct VanDerPol {
    /// Position.
    #[state]
    pub x: f64,
    /// Velocity.
    #[state]
    pub v: f64,
    /// Stiffness μ.
    pub mu: f64,
}

#[system]
impl VanDerPol {
    fn derivative(&self) -> VanDerPolState {
        VanDerPolState {
            x: self.v,
            v: self.mu * (1.0 - self.x * self.x) * self.v - self.x,
        }
    }
}

/// One problem's study: the Rosenbrock methods over rtol = 10⁻³ … 10⁻ᵏ (atol = rtol·`atol`),
/// implicit Euler over `dts`.
fn study<M: Model>(
    name: &str,
    model: &M,
    horizon: f64,
    reference: Vec<f64>,
    (last, atol): (i32, f64),
    dts: Vec<f64>,
    dir: &Path,
) -> odyn::Result<WorkPrecisionSet> {
    let mut study = WorkPrecision::new(name, model.state(), horizon, Reference::Final(reference));
    study.methods = vec![Method::Rodas5P, Method::Rosenbrock23];
    if !dts.is_empty() {
        study.methods.push(Method::ImplicitEuler);
    }
    study.tolerances = WorkPrecision::<M::State>::rtols(3..=last, atol);
    study.dts = dts;
    study.samples = 2;
    study.newton.max_halvings = 30;
    let set = measure(model, &study)?;
    set.write_csv(dir.join(format!("{name}.csv")))?;
    set.plot(
        dir.join(format!("{name}.png")),
        Accuracy::FinalState,
        Cost::Seconds,
    )?;
    set.plot(
        dir.join(format!("{name}_evaluations.png")),
        Accuracy::FinalState,
        Cost::Evaluations,
    )?;
    println!("\n{name} to t = {horizon}:");
    println!(
        "  {:<13} {:>9} {:>9} {:>7} {:>9} {:>9} {:>8} {:>10}",
        "method", "dt/rtol", "error", "steps", "rejected", "f evals", "LU", "time"
    );
    for m in &set.measurements {
        let setting = m
            .setting
            .dt()
            .or(m.setting.rtol())
            .map_or(String::new(), |v| format!("{v:.0e}"));
        println!(
            "  {:<13} {:>9} {:>9.1e} {:>7} {:>9} {:>9} {:>8} {:>8.3} ms",
            format!("{:?}", m.method),
            setting,
            m.error,
            m.stats.steps,
            m.stats.rejected,
            m.stats.function_evaluations(),
            m.stats.factorizations,
            m.seconds * 1e3
        );
    }
    Ok(set)
}

fn main() -> odyn::Result<()> {
    let dir = Path::new("out/stiff_suite");
    let robertson = Robertson {
        a: 1.0,
        b: 0.0,
        c: 0.0,
    };
    // 36-digit Radau IIA (scripts/reference_stiff.py).
    let reference = vec![
        1.786_592_114_209_946_4e-2,
        7.274_751_468_436_319e-8,
        9.821_340_061_103_858e-1,
    ];
    study(
        "robertson",
        &robertson,
        1e5,
        reference,
        (10, 1e-6),
        vec![100.0, 10.0, 1.0, 0.1],
        dir,
    )?;

    // To t = 1e11, where y₂ falls to 1e-13: the test set's rober.f reference (RADAU5 at rtol
    // 1.1e-18 in extended precision). Rosenbrock methods only: implicit Euler would need ~1e6
    // steps of growing size to cross eleven decades.
    let reference = vec![
        0.208_334_014_970_125_5e-7,
        0.833_336_077_033_471_3e-13,
        0.999_999_979_166_505_0,
    ];
    study(
        "robertson_1e11",
        &robertson,
        1e11,
        reference,
        (10, 1e-10),
        Vec::new(),
        dir,
    )?;

    let hires = Hires {
        y: [1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0057],
    };
    // hires.f of the Bari test set (RADAU5 in quadruple precision).
    let reference = vec![
        0.737_131_257_332_566_8e-3,
        0.144_248_572_631_618_5e-3,
        0.588_872_974_096_757_5e-4,
        0.117_565_134_328_314_9e-2,
        0.238_635_619_883_133_1e-2,
        0.623_896_825_274_279_6e-2,
        0.284_999_839_518_576_9e-2,
        0.285_000_160_481_423_1e-2,
    ];
    // 321.8122 is not a multiple of any round dt; fixed steps divide it exactly.
    study(
        "hires",
        &hires,
        321.8122,
        reference,
        (10, 1e-4),
        vec![321.8122 / 1e3, 321.8122 / 1e4, 321.8122 / 1e5],
        dir,
    )?;

    let vdp = VanDerPol {
        x: 2.0,
        v: 0.0,
        mu: 1000.0,
    };
    // vdpolm.f of the Bari test set (problem VDPOLM, t = 2000).
    let reference = vec![0.170_616_773_217_046_9e1, -0.892_809_701_024_812_5e-3];
    study(
        "van_der_pol",
        &vdp,
        2000.0,
        reference,
        (10, 1e-3),
        vec![0.1, 0.01, 0.001],
        dir,
    )?;
    println!(
        "\nwrote {}/{{robertson,robertson_1e11,hires,van_der_pol}}.{{csv,png}}",
        dir.display()
    );
    Ok(())
}
