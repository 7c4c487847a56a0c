//! Attributes read before the kind is chosen: a field attribute a letter or two from one of
//! odyn's (`#[feild]`) is reported and read as the one it misses, so the kind is recognised and
//! nothing else follows from the typo; so is a kernel's method attribute (`#[cel]`).

use syn::{Attribute, ItemImpl, ItemStruct};

use crate::errors::Errors;
use crate::syntax::{FIELD_ATTRIBUTES, RUST_ATTRIBUTES};

/// Reports each field attribute that is neither odyn's nor Rust's: a near miss of one of odyn's
/// (`#[feild]`), or any other when nothing on the struct (a derive, an attribute macro) could
/// own it as a helper. Returns the struct with each near miss read as the attribute it misses, so
/// the kind is recognised and nothing else follows from the typo, and the others removed, so
/// rustc does not report them a second time.
pub(super) fn unknown_attributes(item: &ItemStruct, errors: &mut Errors) -> ItemStruct {
    let helpers_possible = item.attrs.iter().any(|a| {
        !a.path()
            .get_ident()
            .is_some_and(|i| RUST_ATTRIBUTES.contains(&i.to_string().as_str()))
    });
    let mut item = item.clone();
    for field in &mut item.fields {
        check_attributes(
            &mut field.attrs,
            &FIELD_ATTRIBUTES,
            !helpers_possible,
            errors,
        );
    }
    item
}

/// The same for the methods of an impl block whose kernels odyn finds by attribute (`known`:
/// `#[cell]`, `#[pair]`, `#[particle]`): near misses are reported and read as meant. Other
/// attributes may be any attribute macro's.
pub(super) fn unknown_method_attributes(
    known: &[&str],
    imp: &ItemImpl,
    errors: &mut Errors,
) -> ItemImpl {
    let mut imp = imp.clone();
    for member in &mut imp.items {
        if let syn::ImplItem::Fn(f) = member {
            check_attributes(&mut f.attrs, known, false, errors);
        }
    }
    imp
}

/// Reports the attributes of `attrs` that are neither odyn's (`known`) nor Rust's and are at
/// most two edits from one of `known`, or, if `strict`, any such: a near miss becomes the
/// attribute it misses, any other is removed.
fn check_attributes(attrs: &mut Vec<Attribute>, known: &[&str], strict: bool, errors: &mut Errors) {
    attrs.retain_mut(|attr| {
        let Some(ident) = attr.path().get_ident().cloned() else {
            return true;
        };
        let name = ident.to_string();
        if known.contains(&name.as_str()) || RUST_ATTRIBUTES.contains(&name.as_str()) {
            return true;
        }
        let Some((distance, nearest)) = known
            .iter()
            .map(|&k| (edit_distance(&name, k), k))
            .min_by_key(|&(distance, _)| distance)
        else {
            return true;
        };
        let near_miss = distance <= 2;
        if !near_miss && !strict {
            return true;
        }
        // The one it nearly is first, then the others in their order.
        let mut expected = known.to_vec();
        if near_miss {
            expected.retain(|&k| k != nearest);
            expected.insert(0, nearest);
        }
        let expected: Vec<String> = expected.iter().map(|k| format!("`{k}`")).collect();
        let expected = match expected.as_slice() {
            [one] => one.clone(),
            many => format!("one of {}", many.join(", ")),
        };
        errors.at(
            &*attr,
            format_args!("unknown attribute `{name}`; expected {expected}"),
        );
        if near_miss {
            let path = match &mut attr.meta {
                syn::Meta::Path(path) => path,
                syn::Meta::List(list) => &mut list.path,
                syn::Meta::NameValue(pair) => &mut pair.path,
            };
            *path = syn::Ident::new(nearest, ident.span()).into();
        }
        near_miss
    });
}

/// Edits (insertions, deletions, substitutions, swaps of neighbours) that turn `a` into `b`,
/// letters compared without case.
fn edit_distance(a: &str, b: &str) -> usize {
    let a: Vec<char> = a.to_lowercase().chars().collect();
    let b: Vec<char> = b.to_lowercase().chars().collect();
    // d[i][j]: edits from a[..i] to b[..j].
    let mut d = vec![vec![0usize; b.len() + 1]; a.len() + 1];
    for (i, row) in d.iter_mut().enumerate() {
        row[0] = i;
    }
    for (j, cell) in d[0].iter_mut().enumerate() {
        *cell = j;
    }
    for i in 1..=a.len() {
        for j in 1..=b.len() {
            let substitution = usize::from(a[i - 1] != b[j - 1]);
            let mut best = (d[i - 1][j] + 1)
                .min(d[i][j - 1] + 1)
                .min(d[i - 1][j - 1] + substitution);
            if i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1] {
                best = best.min(d[i - 2][j - 2] + 1);
            }
            d[i][j] = best;
        }
    }
    d[a.len()][b.len()]
}

#[cfg(test)]
mod tests {
    use super::edit_distance;

    #[test]
    fn edit_distances() {
        assert_eq!(edit_distance("feild", "field"), 1);
        assert_eq!(edit_distance("postion", "position"), 1);
        assert_eq!(edit_distance("Mass", "mass"), 0);
        assert_eq!(edit_distance("velocty", "velocity"), 1);
        assert_eq!(edit_distance("pin", "pinned"), 3);
        assert_eq!(edit_distance("serde", "state"), 3);
    }
}
