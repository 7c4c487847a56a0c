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

#[path = "common/stiff_models.rs"]
mod stiff_models;

use stiff_models::{Hires, Pollu, Robertson, VanDerPol};

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
        0.999_999_979_166_505,
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

    let pollu = Pollu {
        y: [
            0.0, 0.2, 0.0, 0.04, 0.0, 0.0, 0.1, 0.3, 0.01, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0,
            0.007, 0.0, 0.0, 0.0,
        ],
    };
    // pollu.f of the Bari test set (RADAU5 in quadruple precision).
    let reference = vec![
        0.564_625_548_002_276_9e-1,
        0.134_248_413_042_233_9,
        0.413_973_433_109_942_7e-8,
        0.552_314_020_748_435_9e-2,
        0.201_897_726_230_219_6e-6,
        0.146_454_186_349_396_6e-6,
        0.778_424_911_899_796_4e-1,
        0.324_507_535_339_601_8,
        0.749_401_338_388_040_6e-2,
        0.162_229_315_730_156_1e-7,
        0.113_586_383_325_707_5e-7,
        0.223_050_597_572_135_9e-2,
        0.208_716_288_279_863e-3,
        0.139_692_101_684_015_8e-4,
        0.896_488_485_689_829_5e-2,
        0.435_284_636_933_010_3e-17,
        0.689_921_969_626_340_5e-2,
        0.100_780_303_736_594_6e-3,
        0.177_214_651_396_998_4e-5,
        0.568_294_329_231_639_2e-4,
    ];
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
        "\nwrote {}/{{robertson,robertson_1e11,hires,pollu,van_der_pol}}.{{csv,png}}",
        dir.display()
    );
    Ok(())
}
