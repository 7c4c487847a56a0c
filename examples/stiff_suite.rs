//! Four problems of the Bari stiff test set (Mazzia & Magherini, *Test Set for Initial Value
//! Problem Solvers*, release 2.4, 2008), each solved by the Rosenbrock methods over a sweep of
//! tolerances and by implicit Euler over a sweep of steps, against a reference final state:
//!
//! - `robertson`: Robertson's kinetics to t = 1e5 (reference: the 36-digit Radau IIA run of
//!   `scripts/reference_stiff.py`, which agrees with the test set's value to 2e-14), and
//!   `robertson_1e11` to t = 1e11 (the test set's reference), Rosenbrock methods only;
//! - `hires`: the 8-species HIRES photomorphogenesis model to t = 321.8122 (the test set's
//!   reference);
//! - `pollu`: Verwer's 20-species air-pollution model to t = 60 (the test set's reference);
//! - `van_der_pol`: van der Pol with μ = 1000 to t = 2000 (problem VDPOLM; the test set's
//!   reference), Rosenbrock methods only (see `scripts/vdp_implicit_euler.py` for why).
//!
//! `cargo run --release --example stiff_suite` writes under `out/stiff_suite/`, per problem,
//! `<problem>.csv` (one row per run: method, dt or rtol, steps, rejected, error, time, the
//! evaluations, factorizations and solves), `<problem>.png` (work-precision: max-norm error of
//! the final state against wall time, log-log; lower left is better; `<problem>.svg` is the same
//! chart, where each point shows its dt or rtol on hover) and
//! `<problem>_evaluations.png` (against f, J and ∂f/∂t evaluations).

use std::path::Path;

use odyn::prelude::*;
use odyn::work_precision::{Accuracy, Cost, Reference, WorkPrecision, WorkPrecisionSet, measure};

// The problems and their references, written once for the examples, tests and benches
// (`scenes/src/stiff.rs`).
use scenes::{
    HIRES_REFERENCE, Hires, POLLU_REFERENCE, Pollu, ROBERTSON_1E5, ROBERTSON_1E11, Robertson,
    VAN_DER_POL_2000, VanDerPol,
};

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
    study.title = match name {
        "robertson_1e11" => "Robertson to t = 1e11".to_owned(),
        "hires" => "HIRES".to_owned(),
        "pollu" => "POLLU".to_owned(),
        "van_der_pol" => "Van der Pol, μ = 1000".to_owned(),
        _ => study.title,
    };
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
    for image in ["png", "svg"] {
        set.plot(
            dir.join(format!("{name}.{image}")),
            Accuracy::FinalState,
            Cost::Seconds,
        )?;
    }
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
            .stepping
            .dt()
            .or(m.stepping.rtol())
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

/// Four problems of the Bari stiff test set (Mazzia & Magherini 2008), each solved by the
/// Rosenbrock methods over a sweep of tolerances and by implicit Euler over a sweep of steps,
/// against a reference final state.
///
/// Writes its CSV files and charts under `out/stiff_suite/` (the example's source says what each
/// holds); takes no options.
#[derive(clap::Parser)]
struct Cli {}

fn main() -> odyn::Result<()> {
    <Cli as clap::Parser>::parse();
    let dir = Path::new("out/stiff_suite");
    let robertson = Robertson::classic();
    let reference = ROBERTSON_1E5.to_vec();
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
    let reference = ROBERTSON_1E11.to_vec();
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
    let reference = HIRES_REFERENCE.to_vec();
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

    let pollu = Pollu {
        y: [
            0.0, 0.2, 0.0, 0.04, 0.0, 0.0, 0.1, 0.3, 0.01, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0,
            0.007, 0.0, 0.0, 0.0,
        ],
    };
    let reference = POLLU_REFERENCE.to_vec();
    study(
        "pollu",
        &pollu,
        60.0,
        reference,
        (10, 1e-4),
        vec![0.06, 0.006, 0.0006],
        dir,
    )?;

    let vdp = VanDerPol {
        y1: 2.0,
        y2: 0.0,
        mu: 1000.0,
    };
    // vdpolm.f of the Bari test set (problem VDPOLM, t = 2000). No implicit Euler: at every dt
    // it can afford here (0.1 to 1e-3) it changes sign late, never, or spuriously, so its error
    // at t = 2000 says which branch of the cycle it ends on, not how fast it converges
    // (scripts/vdp_implicit_euler.py).
    let reference = VAN_DER_POL_2000.to_vec();
    study(
        "van_der_pol",
        &vdp,
        2000.0,
        reference,
        (10, 1e-3),
        Vec::new(),
        dir,
    )?;
    println!(
        "\nwrote {}/{{robertson,robertson_1e11,hires,pollu,van_der_pol}}.{{csv,png}}",
        dir.display()
    );
    Ok(())
}
