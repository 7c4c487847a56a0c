use syn::parse_quote;

use super::parse;
use crate::errors::Errors;
use crate::model::{Model, Order};

/// The messages `parse` reports for the impl block `imp` of a model without state.
fn problems(imp: syn::ItemImpl) -> Vec<String> {
    let item: syn::ItemStruct = parse_quote!(
        struct Spring {
            k: f64,
        }
    );
    let model = Model::parameters(&item, Order::Second);
    let mut errors = Errors::default();
    parse(&imp, &model, &mut errors);
    match errors.finish() {
        Ok(()) => Vec::new(),
        Err(e) => e.into_iter().map(|e| e.to_string()).collect(),
    }
}

#[test]
fn helpers_are_found_by_either_spelling_and_called_by_any_form() {
    let item: syn::ItemStruct = parse_quote!(
        struct Spring {
            k: f64,
        }
    );
    let model = Model::parameters(&item, Order::Second);
    let imp: syn::ItemImpl = parse_quote!(impl Spring {
        #[odyn::function] fn a(&self, x: f64) -> f64 { self.k * x }
        #[function] fn b(x: f64, y: [f64; 2]) -> (f64, f64) { (x, y[0]) }
        fn c(x: f64) -> f64 { x }
    });
    let mut errors = Errors::default();
    let helpers = parse(&imp, &model, &mut errors);
    assert!(errors.is_empty());
    assert!(helpers.get("a").is_some() && helpers.get("b").is_some());
    assert!(helpers.get("c").is_none());
    for call in [
        parse_quote!(self.a(1.0)),
        parse_quote!(Self::b(1.0, y)),
        parse_quote!(Spring::b(1.0, y)),
    ] {
        assert!(helpers.called(&call).is_some(), "{}", quote::quote!(#call));
    }
    // The wrong form for the receiver, another type's function, an unmarked one.
    for call in [
        parse_quote!(Self::a(1.0)),
        parse_quote!(self.b(1.0, y)),
        parse_quote!(Other::b(1.0, y)),
        parse_quote!(Self::c(1.0)),
    ] {
        assert!(helpers.called(&call).is_none(), "{}", quote::quote!(#call));
    }
}

/// A cycle is reported once, at the call that closes it, naming the path; a helper calling
/// another twice, or two helpers calling one, is no cycle.
#[test]
fn each_cycle_is_one_error_at_its_closing_call() {
    let found = problems(parse_quote!(impl Spring {
        #[odyn::function] fn a(x: f64) -> f64 { Self::b(x) + Self::b(x) + Self::d(x) }
        #[odyn::function] fn b(x: f64) -> f64 { Self::c(x) }
        #[odyn::function] fn c(x: f64) -> f64 { Self::a(x) + Self::d(x) }
        #[odyn::function] fn d(x: f64) -> f64 { x }
        #[odyn::function] fn e(&self, x: f64) -> f64 { self.e(x) }
    }));
    assert_eq!(found.len(), 2, "{found:?}");
    assert!(found[0].contains("`a` → `b` → `c` → `a`"), "{}", found[0]);
    assert!(
        found[1].starts_with("`#[odyn::function]` `e` calls itself:"),
        "{}",
        found[1]
    );
    assert!(
        problems(parse_quote!(impl Spring {
            #[odyn::function] fn a(x: f64) -> f64 { Self::d(x) * Self::d(x) }
            #[odyn::function] fn b(x: f64) -> f64 { Self::d(x) + Self::a(x) }
            #[odyn::function] fn d(x: f64) -> f64 { x }
        }))
        .is_empty()
    );
}

#[test]
fn signatures_take_and_return_numbers() {
    let found = problems(parse_quote!(impl Spring {
        #[odyn::function] fn a(&mut self, n: usize, (p, q): (f64, f64)) -> bool { true }
        #[odyn::function(fast)] fn b<T>(x: &Vector3<f64>) {}
    }));
    let expected = [
        "takes `&self` or no receiver",
        "takes numbers",
        "takes parameters by name",
        "returns numbers",
        "takes no arguments",
        "cannot be generic",
        "must return a value",
    ];
    assert_eq!(found.len(), expected.len(), "{found:?}");
    for (found, expected) in found.iter().zip(expected) {
        assert!(found.contains(expected), "{found} / {expected}");
    }
}
