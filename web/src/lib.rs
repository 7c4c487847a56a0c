//! The browser lab: six of odyn's scenes compiled to WebAssembly, each a panel the page
//! (`web/index.html`, `web/lab.js`) drives one display frame at a time.
//!
//! - [`SpringLab`] — the spring lab: pick the integrator and dt, watch x(t) and the energy
//!   against the exact solution; explicit Euler's energy grows by 1 + ω²dt² a step.
//! - [`PendulumLab`] — two double pendulums a micro-radian apart, parting.
//! - [`ClothLab`] — one sheet twice, XPBD and implicit Euler side by side, draggable; implicit
//!   Euler solved the Baraff–Witkin way or by the quasi-Newton solve.
//! - [`GrayScottLab`] — Gray–Scott reaction–diffusion with the named patterns.
//! - [`DamBreakLab`] — the SPH dam break.
//! - [`MpmLab`] — jelly, water and snow by the material point method.
//!
//! Each panel advances through odyn's [`odyn::FixedTimestep`] accumulator, so what it computes
//! depends on the simulated time only, never on the display's refresh rate; each exposes
//! `check()`, a fixed run from its default start, and `fingerprint()`, the
//! [`odyn::Fingerprint`] of its state. Built with the `deterministic` feature, the browser's
//! fingerprints equal the native ones (`cargo run -p odyn-web --features deterministic`
//! prints them; `scripts/browser.sh` compares them in headless Chromium).
//!
//! The models live as long as the page: a [`odyn::Stepper`] borrows its model, so each panel
//! leaks its model once (and the Gray–Scott panel once per pattern it has shown).

mod cloth;
mod dam_break;
mod gray_scott;
mod mpm;
mod pendulum;
mod run;
mod spring;

pub use cloth::ClothLab;
pub use dam_break::DamBreakLab;
pub use gray_scott::GrayScottLab;
pub use mpm::MpmLab;
pub use pendulum::PendulumLab;
pub use spring::SpringLab;

/// What a panel method returns to the page: a failure is thrown as its message.
type Js<T> = Result<T, String>;

/// An odyn result for the page.
fn js<T>(result: odyn::Result<T>) -> Js<T> {
    result.map_err(|error| error.to_string())
}

/// A fingerprint as the page shows it: sixteen hex digits.
fn hex(fingerprint: u64) -> String {
    format!("{fingerprint:016x}")
}

/// Every panel's check, natively: its name and fingerprint, in the page's order (the cloth's
/// once for each of implicit Euler's solves: `cloth`, `cloth_qn`).
pub fn fingerprints() -> Js<Vec<(&'static str, String)>> {
    let mut spring = SpringLab::new()?;
    spring.check()?;
    let mut pendulum = PendulumLab::new()?;
    pendulum.check()?;
    let mut cloth = ClothLab::new()?;
    cloth.check()?;
    let mut cloth_qn = ClothLab::new()?;
    cloth_qn.set_solve("quasi_newton")?;
    cloth_qn.check()?;
    let mut gray_scott = GrayScottLab::new()?;
    gray_scott.check()?;
    let mut dam_break = DamBreakLab::new()?;
    dam_break.check()?;
    let mut mpm = MpmLab::new()?;
    mpm.check()?;
    Ok(vec![
        ("spring", spring.fingerprint()),
        ("pendulum", pendulum.fingerprint()),
        ("cloth", cloth.fingerprint()),
        ("cloth_qn", cloth_qn.fingerprint()),
        ("gray_scott", gray_scott.fingerprint()),
        ("dam_break", dam_break.fingerprint()),
        ("mpm", mpm.fingerprint()),
    ])
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every panel's check runs natively and gives the same fingerprint twice (the check
    /// restarts its panel), so the browser has one value to equal.
    #[test]
    fn every_check_runs_and_repeats_itself() {
        let first = fingerprints().unwrap();
        assert_eq!(first.len(), 7);
        assert_eq!(first, fingerprints().unwrap());
    }

    /// On ẍ = −x, explicit Euler maps (x, v) by a matrix √(1 + dt²) times a rotation, so the
    /// energy grows by exactly 1 + dt² a step (up to rounding): what the panel annotates.
    #[test]
    fn explicit_euler_energy_grows_by_one_plus_dt_squared() {
        let mut lab = SpringLab::new().unwrap();
        lab.restart("explicit_euler", 0.05).unwrap();
        for _ in 0..120 {
            lab.frame(1.0 / 60.0).unwrap();
        }
        assert!(lab.steps() > 30.0, "{} steps", lab.steps());
        let (measured, theory) = (lab.growth_per_step(), lab.explicit_euler_growth());
        assert!((measured - theory).abs() < 1e-12, "{measured} vs {theory}");
        assert_eq!(theory, 1.0025);
        // Symplectic Euler keeps it bounded instead: within dt/2·ω of E₀ = ½ (its modified
        // energy differs from E by O(dt)).
        lab.restart("symplectic_euler", 0.05).unwrap();
        for _ in 0..600 {
            lab.frame(1.0 / 60.0).unwrap();
        }
        assert!(
            (lab.energy() / 0.5 - 1.0).abs() < 0.05 / 2.0 + 1e-12,
            "{}",
            lab.energy()
        );
    }

    /// A frame of 1/60 s at dt = 0.02 takes no step or one, and 60 frames take the 50 steps one
    /// second holds: the accumulator keeps the remainder.
    #[test]
    fn frames_take_the_steps_the_elapsed_time_holds() {
        let mut lab = SpringLab::new().unwrap();
        let taken: u32 = (0..60).map(|_| lab.frame(1.0 / 60.0).unwrap()).sum();
        assert!((49..=50).contains(&taken), "{taken}");
        assert_eq!(lab.steps(), f64::from(taken));
    }

    /// A grabbed particle of the cloth sits where it is held, in both cloths, and nothing is
    /// grabbed far from every particle or at a pinned corner.
    #[test]
    fn the_cloth_follows_the_hand() {
        let mut lab = ClothLab::new().unwrap();
        // The free far corner (row 15, column 15) starts at (1, 0, 1): on screen (1.4, 0.25).
        assert!(lab.grab(1.41, 0.26, 0.05));
        lab.drag(1.2, -0.3);
        lab.frame(1.0 / 60.0).unwrap();
        lab.drag(1.2, -0.3);
        lab.frame(1.0 / 60.0).unwrap();
        let points = lab.points();
        let n = points.len() / 4;
        let corner = cloth::SIDE * cloth::SIDE - 1;
        for cloth in 0..2 {
            let (x, y) = (
                points[2 * (cloth * n + corner)],
                points[2 * (cloth * n + corner) + 1],
            );
            // Held through the step (XPBD) or put back after it (implicit Euler): there, up to
            // the rounding of the projection.
            assert!(
                (x - 1.2).abs() < 1e-12 && (y + 0.3).abs() < 1e-12,
                "cloth {cloth}: ({x}, {y})"
            );
        }
        lab.release();
        assert!(!lab.grab(5.0, 5.0, 0.05));
        // The pinned corner (0, 0, 0) is on screen at the origin: never grabbed.
        let mut fresh = ClothLab::new().unwrap();
        assert!(!fresh.grab(0.0, 0.0, 0.01));
    }

    /// The quasi-Newton solve in the panel: dragged, the cloth follows the hand as the
    /// Baraff–Witkin one does, and its link Laplacian is factorized once over two seconds
    /// (Baraff–Witkin: once a step); an unknown solve is an error naming the known ones.
    #[test]
    fn the_quasi_newton_cloth_follows_the_hand_on_one_factorization() {
        let mut lab = ClothLab::new().unwrap();
        let error = lab.set_solve("newton").unwrap_err();
        assert!(error.contains("quasi_newton"), "{error}");
        lab.set_solve("quasi_newton").unwrap();
        assert!(lab.method().contains("quasi-Newton"), "{}", lab.method());
        assert_eq!(lab.check().unwrap(), 120);
        assert_eq!(lab.factorizations(), 1.0);
        // The implicit cloth's free far corner, the last of the drawn points, where it is now.
        let corner = 2 * cloth::SIDE * cloth::SIDE - 1;
        let at = |lab: &ClothLab| {
            let points = lab.points();
            (points[2 * corner], points[2 * corner + 1])
        };
        let (sx, sy) = at(&lab);
        assert!(lab.grab(sx, sy, 0.05));
        lab.drag(1.2, -0.3);
        lab.frame(1.0 / 60.0).unwrap();
        let (x, y) = at(&lab);
        assert!(
            (x - 1.2).abs() < 1e-12 && (y + 0.3).abs() < 1e-12,
            "({x}, {y})"
        );
        let mut direct = ClothLab::new().unwrap();
        direct.check().unwrap();
        assert_eq!(direct.factorizations(), 120.0);
    }
}
