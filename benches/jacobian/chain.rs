//! A chain of 8 masses between fixed ends (16 state components), written for 8 and for any N
//! (`struct Chain<const N: usize>`): the generated exact Jacobian against the const-generic
//! model's central differences, and what each costs a Rodas5P run to t = 1.

use super::*;
use odyn::Method;

/// The chain for 8 masses: an exact, generated Jacobian.
#[system]
#[derive(Clone, Copy)]
pub struct Eight {
    #[position]
    x: [f64; 8],
    #[velocity]
    v: [f64; 8],
    k: f64,
}

#[system]
#[allow(
    clippy::needless_range_loop,
    reason = "a stencil reads its neighbours by index"
)]
impl Eight {
    fn acceleration(&self) -> [f64; 8] {
        let mut a = [0.0; 8];
        for i in 0..8 {
            let left = if i > 0 { self.x[i - 1] } else { 0.0 };
            let right = if i + 1 < 8 { self.x[i + 1] } else { 0.0 };
            a[i] = self.k * (left - 2.0 * self.x[i] + right) - 0.1 * self.v[i];
        }
        a
    }
}

/// The same chain for any N, `$name` under `#[system($($args)*)]`: its Jacobian is central
/// differences of f, or dual numbers.
macro_rules! any {
    ($name:ident, $($args:tt)*) => {
        #[system($($args)*)]
        #[derive(Clone, Copy)]
        pub struct $name<const N: usize> {
            #[position]
            x: [f64; N],
            #[velocity]
            v: [f64; N],
            k: f64,
        }

        #[system]
        #[allow(
            clippy::needless_range_loop,
            reason = "a stencil reads its neighbours by index"
        )]
        impl<const N: usize> $name<N> {
            fn acceleration(&self) -> [f64; N] {
                let mut a = [0.0; N];
                for i in 0..N {
                    let left = if i > 0 { self.x[i - 1] } else { 0.0 };
                    let right = if i + 1 < N { self.x[i + 1] } else { 0.0 };
                    a[i] = self.k * (left - 2.0 * self.x[i] + right) - 0.1 * self.v[i];
                }
                a
            }
        }
    };
}

any!(Any,);
any!(AnyDual, jacobian = dual);

fn any_dual() -> (AnyDual<8>, AnyDualState<8>) {
    let model = AnyDual {
        x: start(),
        v: [0.0; 8],
        k: 1e4,
    };
    black_box((model, model.state()))
}

fn start() -> [f64; 8] {
    std::array::from_fn(|i| 0.1 * (i as f64 + 1.0).sin())
}

fn eight() -> (Eight, EightState) {
    let model = Eight {
        x: start(),
        v: [0.0; 8],
        k: 1e4,
    };
    black_box((model, model.state()))
}

fn any() -> (Any<8>, AnyState<8>) {
    let model = Any {
        x: start(),
        v: [0.0; 8],
        k: 1e4,
    };
    black_box((model, model.state()))
}

fn rodas5p<M: Model>(model: M) -> M::State {
    let run = model
        .simulate()
        .integrator(Method::Rodas5P)
        .tolerances(1e-8, 1e-10)
        .duration(1.0)
        .record_every(u64::MAX)
        .run()
        .expect("the chain runs");
    run.last().state.clone()
}

/// ∂f/∂y into a matrix allocated once, as a run does.
fn jacobian<M: Jacobian>(bencher: divan::Bencher, (model, y): (M, M::State)) {
    let mut j = model.jacobian_matrix(&y);
    bencher.bench_local(|| {
        model.jacobian(0.0, black_box(&y), &mut j);
        black_box(&j);
    });
}

#[divan::bench]
fn generated_jacobian(bencher: divan::Bencher) {
    jacobian(bencher, eight());
}

#[divan::bench]
fn const_generic_differences(bencher: divan::Bencher) {
    jacobian(bencher, any());
}

#[divan::bench]
fn const_generic_dual(bencher: divan::Bencher) {
    jacobian(bencher, any_dual());
}

#[divan::bench]
#[inline(never)]
fn const_generic_dual_rodas5p() -> AnyDualState<8> {
    rodas5p(any_dual().0)
}

#[divan::bench]
#[inline(never)]
fn generated_rodas5p() -> EightState {
    rodas5p(eight().0)
}

#[divan::bench]
#[inline(never)]
fn const_generic_rodas5p() -> AnyState<8> {
    rodas5p(any().0)
}
