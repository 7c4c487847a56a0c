//! Fitting a stiff model: the three rate constants of Robertson's kinetics (A → B at k₁,
//! B + C → A + C at k₂, 2B → B + C at k₃; `scenes::Robertson`, whose rates are `#[param]`s),
//! recovered from noisy concentrations by `odyn::fit` — Levenberg–Marquardt on the forward
//! sensitivities, the model and its sensitivities solved by Rodas5P on the augmented Jacobian.
//!
//! The rates span nine orders of magnitude (0.04, 10⁴, 3·10⁷), so the fit searches ln k. The
//! "measurements" are synthetic, so the answer is known: a, b and c at 41 times spaced evenly in
//! log t from 10⁻⁵ to 10⁵ (the fast transient of b, set by k₃ and k₂, through the slow decay of
//! a, set by k₁), each with Gaussian noise of 1 % of its value (a seeded generator: the run is
//! reproducible), weighted by 1/σ. The fit starts from k = (0.01, 10⁵, 10⁶) — off by 4×, 10× and
//! 30×.
//!
//! `cargo run --release --example fit_robertson` writes `out/fit_robertson/fit.csv` (time, data,
//! initial guess, fitted model, truth, for each species) and `fit.png`, and prints the fit's wall
//! time; `scripts/scipy_fit_robertson.py` runs it and the same fit in SciPy side by side.

use std::f64::consts::PI;
use std::path::Path;
use std::process::ExitCode;
use std::time::Instant;

use odyn::Parameters;
use odyn::fit::{Data, FitOptions, fit};
use odyn::output::{number, write_table};
use odyn::plot::{Chart, Series};
use odyn::prelude::*;
use odyn::rand::rngs::StdRng;
use odyn::rand::{Rng, SeedableRng};

// The model, written once for the examples, tests and benches (`scenes/src/stiff.rs`).
use scenes::Robertson;

/// Relative noise of every measurement.
const NOISE: f64 = 0.01;

fn main() -> ExitCode {
    match run(Path::new("out/fit_robertson")) {
        Ok(()) => ExitCode::SUCCESS,
        Err(error) => {
            eprintln!("error: {error}");
            ExitCode::FAILURE
        }
    }
}

/// (a, b, c) at `times` for `model`.
fn concentrations(model: &Robertson, times: &[f64]) -> odyn::Result<Vec<[f64; 3]>> {
    let run = model
        .simulate()
        .integrator(Method::Rodas5P)
        .tolerances(1e-10, 1e-16)
        .duration(*times.last().unwrap_or(&0.0))
        .save_at(times)
        .run()?;
    times
        .iter()
        .map(|&t| {
            let s = run.sample_at(t)?.state;
            Ok([s.a, s.b, s.c])
        })
        .collect()
}

fn run(dir: &Path) -> odyn::Result<()> {
    let truth = Robertson::classic();
    let times: Vec<f64> = (0..=40)
        .map(|k| 10f64.powf(-5.0 + 0.25 * k as f64))
        .collect();
    let exact = concentrations(&truth, &times)?;
    // Gaussian noise by Box–Muller from a seeded generator, 1 % of each value.
    let mut rng = StdRng::seed_from_u64(1966);
    let mut normal = move || {
        let (u, v): (f64, f64) = (rng.random(), rng.random());
        (-2.0 * (1.0 - u).ln()).sqrt() * (2.0 * PI * v).cos()
    };
    let data: Vec<Data> = (0..3)
        .map(|species| {
            let values: Vec<f64> = exact
                .iter()
                .map(|y| y[species] * (1.0 + NOISE * normal()))
                .collect();
            Data {
                component: species,
                times: times.clone(),
                weights: values.iter().map(|v| 1.0 / (NOISE * v.abs())).collect(),
                values,
            }
        })
        .collect();
    let guess = Robertson {
        k1: 0.01,
        k2: 1e5,
        k3: 1e6,
        ..truth
    };
    let options = FitOptions {
        integrator: Method::Rodas5P,
        rtol: 1e-8,
        atol: 1e-16,
        log_parameters: true,
        ..FitOptions::default()
    };
    // The fit's wall time, best of five (it is deterministic: each run is the same work).
    let mut seconds = f64::INFINITY;
    let mut found = None;
    for _ in 0..5 {
        let started = Instant::now();
        found = Some(fit(&guess, &data, &options)?);
        seconds = seconds.min(started.elapsed().as_secs_f64());
    }
    let found = found.expect("five fits ran");
    let m = 3 * times.len();
    println!(
        "fitted in {} iterations ({} solves with sensitivities) in {:.2} ms (best of 5); cost \
         {:.4e} → {:.2} (≈ (m − n)/2 = {} for noise of the assumed σ)",
        found.iterations,
        found.solves,
        1e3 * seconds,
        found.initial_cost,
        found.cost,
        (m - 3) / 2
    );
    println!(
        "{:>4}{:>12}{:>12}{:>14}{:>12}{:>10}",
        "", "truth", "guess", "fitted", "std error", "z"
    );
    for (j, name) in Robertson::NAMES.iter().enumerate() {
        let (p, s) = (found.parameters[j], found.standard_errors[j]);
        println!(
            "{name:>4}{:>12.4e}{:>12.4e}{:>14.6e}{:>12.2e}{:>10.2}",
            truth.parameters()[j],
            guess.parameters()[j],
            p,
            s,
            (p - truth.parameters()[j]) / s
        );
    }
    let mut fitted = guess;
    fitted.set_parameters(&found.parameters)?;
    let fine: Vec<f64> = (0..=400)
        .map(|k| 10f64.powf(-5.0 + 0.025 * k as f64))
        .collect();
    let (initial, best) = (
        concentrations(&guess, &fine)?,
        concentrations(&fitted, &fine)?,
    );
    let at_samples = [
        concentrations(&guess, &times)?,
        concentrations(&fitted, &times)?,
        exact,
    ];
    let mut rows = Vec::new();
    for (k, t) in times.iter().enumerate() {
        for (species, name) in ["a", "b", "c"].iter().enumerate() {
            rows.push(vec![
                number(*t),
                (*name).to_owned(),
                number(data[species].values[k]),
                number(at_samples[0][k][species]),
                number(at_samples[1][k][species]),
                number(at_samples[2][k][species]),
            ]);
        }
    }
    write_table(
        dir.join("fit.csv"),
        &["t", "species", "data", "initial_guess", "fitted", "truth"],
        &rows,
    )?;
    // b is drawn ×10⁴, as in Hairer & Wanner's figure of the problem.
    let scale = [1.0, 1e4, 1.0];
    let curve = |values: &[[f64; 3]], species: usize| -> Vec<(f64, f64)> {
        fine.iter()
            .zip(values)
            .map(|(t, y)| (*t, scale[species] * y[species]))
            .collect()
    };
    let mut series = Vec::new();
    for (species, name) in ["a", "10⁴·b", "c"].iter().enumerate() {
        let points = times
            .iter()
            .zip(&data[species].values)
            .map(|(t, v)| (*t, scale[species] * v))
            .collect();
        series.push(Series::markers(format!("{name} data"), points));
        series.push(Series::line(
            format!("{name} guess"),
            curve(&initial, species),
        ));
        series.push(Series::line(
            format!("{name} fitted"),
            curve(&best, species),
        ));
    }
    Chart {
        title: format!(
            "Robertson: k₁ = {:.4} ± {:.4}, k₂ = {:.3e} ± {:.1e}, k₃ = {:.4e} ± {:.1e} fitted",
            found.parameters[0],
            found.standard_errors[0],
            found.parameters[1],
            found.standard_errors[1],
            found.parameters[2],
            found.standard_errors[2]
        ),
        note: "truth 0.04, 1e4, 3e7; 41 times × 3 species, 1 % noise; guess 0.01, 1e5, 1e6; \
               Rodas5P with sensitivities, ln k searched"
            .into(),
        x_label: "t".into(),
        y_label: "concentration".into(),
        log_x: true,
        series,
        ..Chart::default()
    }
    .write(dir.join("fit.png"), (1000, 600))?;
    println!("wrote out/fit_robertson/fit.csv and fit.png");
    Ok(())
}
