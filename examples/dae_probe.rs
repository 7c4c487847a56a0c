use odyn::prelude::*;
use scenes::*;
use std::time::Instant;

fn rel(x: &[f64], r: &[f64]) -> f64 {
    x.iter().zip(r).filter(|(_, r)| r.abs() >= 1e-10).map(|(x, r)| ((x - r) / r).abs()).fold(0.0, f64::max)
}

fn main() -> odyn::Result<()> {
    for method in [Method::Rodas5P, Method::Rosenbrock23] {
        for rtol in [1e-4, 1e-6, 1e-8] {
            let t = Instant::now();
            let r = RobertsonDae::classic().simulate().integrator(method).tolerances(rtol, rtol * 1e-8).duration(1e11).record_every(u64::MAX).run_partial()?;
            let s = r.0.last().state;
            println!("rober {method} {rtol:e}: err {:.2e} {} {:?} {:?}", rel(s.as_slice(), &ROBERTSON_DAE_1E11), r.0.stats, t.elapsed(), r.1);
            let t = Instant::now();
            let r = ChemAkzo::start().simulate().integrator(method).tolerances(rtol, rtol * 1e-4).duration(180.0).record_every(u64::MAX).run_partial()?;
            let s = r.0.last().state;
            println!("akzo {method} {rtol:e}: err {:.2e} {} {:?} {:?}", rel(s.as_slice(), &CHEMAKZO_REFERENCE), r.0.stats, t.elapsed(), r.1);
            let t = Instant::now();
            let r = Transamp::start().simulate().integrator(method).tolerances(rtol, rtol * 1e-4).duration(0.2).record_every(u64::MAX).run_partial()?;
            let s = r.0.last().state;
            println!("transamp {method} {rtol:e}: err {:.2e} {} {:?} {:?}", rel(s.as_slice(), &TRANSAMP_REFERENCE), r.0.stats, t.elapsed(), r.1);
            for (a, b) in [(0.0, 0.0), (10.0, 10.0)] {
                let t = Instant::now();
                let r = CartesianPendulum::released(a, b).simulate().integrator(method).tolerances(rtol, rtol).duration(10.0).record_every(u64::MAX).run_partial()?;
                let s = r.0.last().state;
                let drift = s.x * s.x + s.y * s.y - 1.0;
                println!("pendulum({a}) {method} {rtol:e}: err {:.2e} drift {drift:.1e} {} {:?} {:?}", rel(s.as_slice(), &PENDULUM_10), r.0.stats, t.elapsed(), r.1);
            }
        }
    }
    Ok(())
}
