//! odyn on the DAE bench's problems: the `scenes` models (`scenes/src/dae.rs`) under one of
//! its methods that take a mass matrix.

use super::problems::Dae;

/// odyn on the `scenes` model of `dae` (`None` for `transamp_se`, which odyn does not need).
pub fn solve(dae: &Dae, method: odyn::Method, rtol: f64, atol: f64) -> Option<crate::Run> {
    fn run<M: odyn::Model>(
        model: &M,
        method: odyn::Method,
        rtol: f64,
        atol: f64,
        t_end: f64,
    ) -> Option<crate::Run> {
        let trajectory = odyn::Simulation::new(model)
            .integrator(method)
            .tolerances(rtol, atol)
            .duration(t_end)
            .record_every(u64::MAX)
            .run()
            .map_err(|e| {
                if std::env::var_os("PEERS_SWEEP").is_some() {
                    eprintln!("    odyn: {e}");
                }
            })
            .ok()?;
        let s = trajectory.stats;
        Some(crate::Run {
            y: odyn::State::as_slice(&trajectory.last().state).to_vec(),
            steps: s.steps,
            rejected: s.rejected,
            evaluations: s.evaluations,
            jacobians: s.jacobian_evaluations,
            factorizations: s.factorizations,
        })
    }
    match dae.name {
        "chemakzo" => run(&scenes::ChemAkzo::start(), method, rtol, atol, dae.t_end),
        "transamp" => run(&scenes::Transamp::start(), method, rtol, atol, dae.t_end),
        "roberdae" => run(
            &scenes::RobertsonDae::classic(),
            method,
            rtol,
            atol,
            dae.t_end,
        ),
        _ => None,
    }
}
