//! A smoke plume with Stam's Stable Fluids: buoyant smoke rising from a source in a closed box.
//!
//! The box is 96×128 cells (1 × 1.33 units), inviscid; a disc near the bottom keeps emitting
//! smoke of density 1 with an upward velocity of 1, and the smoke's buoyancy (4 units of upward
//! acceleration per unit density) lifts it. The step is fixed at Δt = 0.02, so the CFL number
//! max|u|·Δt/h exceeds 1 once the plume accelerates: semi-Lagrangian advection stays stable at
//! any CFL. After every step the example checks the discrete divergence.
//!
//! `cargo run --release --example smoke` writes under `out/smoke/`: `smoke.gif` (the density
//! every 5 steps), `frame_2s.png`, `frame_4s.png`, `frame_6s.png` and `smoke.csv` (time, CFL
//! number, max |divergence|, kinetic energy, smoke in the box).

use std::path::Path;
use std::time::Instant;

use odyn::fluids::{FluidOptions, StableFluids};
use odyn::output::{number, write_table};
use odyn::plot::{Field, FieldStyle, field_animation, field_image};

/// A smoke plume with Stam's Stable Fluids: buoyant smoke rising from a source in a closed box.
///
/// Writes its CSV files and charts under `out/smoke/` (the example's source says what each
/// holds).
#[derive(clap::Parser)]
struct Cli {
    /// Frames of `smoke.gif`, at most 60 (60: ~2.2 MB)
    #[arg(long, default_value_t = 60)]
    gif_frames: usize,
}

fn main() -> odyn::Result<()> {
    let cli = <Cli as clap::Parser>::parse();
    let dir = Path::new("out/smoke");
    let (nx, ny) = (96, 128);
    let h = 1.0 / nx as f64;
    let mut fluid = StableFluids::new(FluidOptions {
        nx,
        ny,
        cell: h,
        viscosity: 0.0,
        buoyancy: 4.0,
    })?;
    let dt = 0.02;
    let steps = 300;
    let source = |i: usize, j: usize| {
        let (x, y) = ((i as f64 + 0.5) * h, (j as f64 + 0.5) * h);
        (x - 0.5).powi(2) + (y - 0.12).powi(2) < 0.06f64.powi(2)
    };
    let style = FieldStyle {
        range: (0.0, 1.0),
        scale: 3,
        ..FieldStyle::default()
    };
    let mut frames: Vec<(f64, Vec<f64>)> = Vec::new();
    let mut rows = Vec::new();
    let (mut worst_divergence, mut worst_cfl) = (0.0f64, 0.0f64);
    let started = Instant::now();
    for step in 1..=steps {
        for j in 0..ny {
            for i in 0..nx {
                if source(i, j) {
                    fluid.density[i + j * nx] = 1.0;
                    fluid.v[i + j * nx] = 1.0;
                    fluid.v[i + (j + 1) * nx] = 1.0;
                }
            }
        }
        let cfl = fluid.max_speed() * dt / h;
        fluid.step(dt)?;
        let divergence = fluid
            .divergence()
            .iter()
            .fold(0.0f64, |m, d| m.max(d.abs()));
        (worst_divergence, worst_cfl) = (worst_divergence.max(divergence), worst_cfl.max(cfl));
        let t = step as f64 * dt;
        rows.push(vec![
            number(t),
            number(cfl),
            number(divergence),
            number(fluid.kinetic_energy()),
            number(fluid.density.iter().sum::<f64>() * h * h),
        ]);
        if step % 5 == 0 {
            frames.push((t, fluid.density.clone()));
        }
        if step % 100 == 0 {
            let field = Field::new(nx, ny, &fluid.density)
                .titled("Smoke plume")
                .named("density")
                .at_time(t);
            field_image(dir.join(format!("frame_{}s.png", t.round())), field, style)?;
        }
    }
    let elapsed = started.elapsed().as_secs_f64();
    println!(
        "Smoke plume, {nx}×{ny} cells, Δt = {dt}, {steps} steps: {:.2} ms a step; largest CFL \
         number {worst_cfl:.2}; largest |divergence| after a step {worst_divergence:.1e}",
        1e3 * elapsed / steps as f64
    );
    write_table(
        dir.join("smoke.csv"),
        &["t", "cfl", "max_divergence", "kinetic_energy", "smoke"],
        &rows,
    )?;
    let stride = frames.len().div_ceil(cli.gif_frames.max(1));
    let fields: Vec<Field<'_>> = frames
        .iter()
        .step_by(stride)
        .map(|(t, values)| {
            Field::new(nx, ny, values)
                .titled("Smoke plume")
                .named("density")
                .at_time(*t)
        })
        .collect();
    field_animation(dir.join("smoke.gif"), &fields, style, 50 * stride as u32)?;
    println!("wrote out/smoke/");
    Ok(())
}
