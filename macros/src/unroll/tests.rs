use quote::ToTokens;
use syn::{Block, parse_quote};

use super::unroll;

fn same(actual: &Block, expected: &Block) {
    assert_eq!(
        actual.to_token_stream().to_string(),
        expected.to_token_stream().to_string()
    );
}

#[test]
fn a_pair_loop_is_copied_in_order_with_its_variables_bound() {
    let body: Block = parse_quote!({
        for i in 0..3 {
            for j in (i + 1)..3 {
                f(i, j);
            }
        }
    });
    // The inner bounds read `i`, so `j` is bound through the array that gives it `i`'s type.
    let expected: Block = parse_quote!({
        {
            {
                let i = 0;
                {
                    {
                        let j = [(i + 1), 3, 1][2];
                        f(i, j);
                    }
                    {
                        let j = [(i + 1), 3, 2][2];
                        f(i, j);
                    }
                }
            }
            {
                let i = 1;
                {
                    {
                        let j = [(i + 1), 3, 2][2];
                        f(i, j);
                    }
                }
            }
            {
                let i = 2;
                {}
            }
        }
    });
    same(&unroll(&body), &expected);
}

#[test]
fn inclusive_suffixed_and_negative_ranges() {
    let body: Block = parse_quote!({
        for k in -1..=0 {
            g(k);
        }
        for n in 0usize..1 {
            h(n);
        }
        for _ in 0..2 {
            tick();
        }
    });
    let expected: Block = parse_quote!({
        {
            {
                let k = [-1, 0, (-1)][2];
                g(k);
            }
            {
                let k = [-1, 0, 0][2];
                g(k);
            }
        }
        {
            {
                let n = [0usize, 1, 0][2];
                h(n);
            }
        }
        {
            {
                let _ = 0;
                tick();
            }
            {
                let _ = 1;
                tick();
            }
        }
    });
    same(&unroll(&body), &expected);
}

#[test]
fn loops_left_early_or_with_unknown_bounds_stay_loops() {
    for body in [
        parse_quote!({
            for i in 0..3 {
                if x[i] > 0.0 {
                    break;
                }
            }
        }),
        parse_quote!({
            for i in 0..3 {
                if x[i] > 0.0 {
                    continue;
                }
            }
        }),
        parse_quote!({
            'outer: for i in 0..3 {
                y += x[i];
            }
        }),
        parse_quote!({
            'outer: loop {
                for i in 0..3 {
                    break 'outer;
                }
            }
        }),
        parse_quote!({
            for i in 0..3 {
                debug_assert!(x[i] > 0.0);
            }
        }),
        parse_quote!({
            for i in 0..n {
                y += x[i];
            }
        }),
        parse_quote!({
            for i in (0..3).rev() {
                y += x[i];
            }
        }),
        parse_quote!({
            for (i, v) in [(0, 1.0)] {
                y += v;
            }
        }),
    ] {
        same(&unroll(&body), &body);
    }
}

#[test]
fn a_break_of_an_inner_loop_keeps_only_that_loop() {
    let body: Block = parse_quote!({
        for i in 0..2 {
            for j in 0..2 {
                if j > i {
                    break;
                }
            }
        }
    });
    let expected: Block = parse_quote!({
        {
            {
                let i = 0;
                for j in 0..2 {
                    if j > i {
                        break;
                    }
                }
            }
            {
                let i = 1;
                for j in 0..2 {
                    if j > i {
                        break;
                    }
                }
            }
        }
    });
    same(&unroll(&body), &expected);
}

#[test]
fn a_variable_bound_again_or_mutable_is_not_known_inside() {
    // `i` is shadowed, then mutated: the inner bounds are no longer the iteration's number.
    for body in [
        parse_quote!({
            for i in 0..2 {
                let i = 5;
                for j in i..7 {
                    f(j);
                }
            }
        }),
        parse_quote!({
            for mut i in 0..2 {
                i += 1;
                for j in i..7 {
                    f(j);
                }
            }
        }),
    ] {
        let unrolled = unroll(&body).to_token_stream().to_string();
        assert_eq!(unrolled.matches("for j in i .. 7").count(), 2, "{unrolled}");
    }
}

#[test]
fn a_function_over_budget_is_emitted_as_written() {
    let body: Block = parse_quote!({
        for i in 0..2 {
            f(i);
        }
        for i in 0..20 {
            for j in 0..20 {
                f(i, j);
            }
        }
    });
    same(&unroll(&body), &body);
}

#[test]
fn ranges_too_long_to_count_are_emitted_as_written_without_a_panic() {
    // Each of these overflows arithmetic on its bounds or the budget's product.
    for body in [
        parse_quote!({
            for i in 0..18446744073709551615 {
                f(i);
            }
        }),
        parse_quote!({
            for i in
                -170141183460469231731687303715884105728..170141183460469231731687303715884105727
            {
                f(i);
            }
        }),
        parse_quote!({
            for i in 0..9223372036854775807 {
                for j in 0..9223372036854775807 {
                    f(i, j);
                }
            }
        }),
    ] {
        same(&unroll(&body), &body);
    }
}

#[test]
fn an_inner_loop_of_the_same_name_hides_the_outer_value() {
    // The outer `i` is bound again by the inner loop, so it is not known inside: the loop over
    // `j`, bounded by it, stays a loop (it would read 5, never the inner loop's 0 or 1).
    let body: Block = parse_quote!({
        for i in 5..6 {
            for i in 0..2 {
                f(i);
            }
            for j in i..7 {
                g(j);
            }
        }
    });
    let unrolled = unroll(&body).to_token_stream().to_string();
    assert!(unrolled.contains("let i = 0 ; f (i) ;"), "{unrolled}");
    assert_eq!(unrolled.matches("for j in i .. 7").count(), 1, "{unrolled}");
}
