//! The guide's chapters (`docs/book/src/*.md`) as doctests: every ```` ```rust ```` block of every
//! chapter is compiled and run by `cargo test --workspace`, and a unit test checks that the
//! chapters listed here are exactly the ones `SUMMARY.md` lists.

/// One `#[cfg(doctest)]` item per chapter, its docs the chapter, and the list of the chapters.
macro_rules! chapters {
    ($($item:ident: $file:literal),* $(,)?) => {
        $(
            #[cfg(doctest)]
            #[doc = include_str!(concat!("../docs/book/src/", $file))]
            pub struct $item;
        )*

        /// The chapters that have a doctest item, in `SUMMARY.md`'s order.
        #[cfg(test)]
        const CHAPTERS: &[&str] = &[$($file),*];
    };
}

// A new chapter: its file under docs/book/src/, its line in SUMMARY.md, and its line here.
chapters! {
    Introduction: "introduction.md",
    Models: "models.md",
    Runs: "runs.md",
    Integrators: "integrators.md",
    Adaptive: "adaptive.md",
    Jacobians: "jacobians.md",
    Stiff: "stiff.md",
    LinearSolvers: "linear-solvers.md",
    Dae: "dae.md",
    Fitting: "fitting.md",
    Stability: "stability.md",
    Scenes: "scenes.md",
    Ensembles: "ensembles.md",
    Distributed: "distributed.md",
    Determinism: "determinism.md",
    Particles: "particles.md",
    Fields: "fields.md",
    ConstraintsFluids: "constraints-fluids.md",
    Hybrid: "hybrid.md",
}

#[cfg(test)]
mod tests {
    use super::CHAPTERS;

    /// The chapter files `SUMMARY.md` links to, in order: every `(file.md)` link outside HTML
    /// comments (where the chapters still to come wait), draft chapters (`()`) left out.
    fn summary_chapters(summary: &str) -> Vec<String> {
        let mut text = String::new();
        let mut rest = summary;
        while let Some(start) = rest.find("<!--") {
            text.push_str(&rest[..start]);
            rest = rest[start..]
                .find("-->")
                .map_or("", |end| &rest[start + end + 3..]);
        }
        text.push_str(rest);
        text.split("](")
            .skip(1)
            .filter_map(|after| after.split_once(')').map(|(link, _)| link.trim()))
            .filter(|link| !link.is_empty())
            .map(str::to_owned)
            .collect()
    }

    #[test]
    fn every_chapter_in_the_summary_is_a_doctest_and_back() {
        let summary = include_str!("../docs/book/src/SUMMARY.md");
        assert_eq!(summary_chapters(summary), CHAPTERS);
    }

    #[test]
    fn every_chapter_file_is_in_the_summary() {
        let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("docs/book/src");
        let mut files: Vec<String> = std::fs::read_dir(&dir)
            .expect("docs/book/src is readable")
            .map(|entry| entry.expect("a directory entry").file_name())
            .filter_map(|name| name.to_str().map(str::to_owned))
            .filter(|name| name.ends_with(".md") && name != "SUMMARY.md")
            .collect();
        files.sort();
        let mut listed: Vec<String> = CHAPTERS.iter().map(|c| (*c).to_owned()).collect();
        listed.sort();
        assert_eq!(
            files, listed,
            "a chapter file without a SUMMARY.md line, or the reverse"
        );
    }

    #[test]
    fn the_summary_parser_skips_comments_and_drafts() {
        let summary = "# Summary\n[Intro](a.md)\n- [B](b.md)\n<!-- - [C](c.md) -->\n- [D]()\n";
        assert_eq!(summary_chapters(summary), ["a.md", "b.md"]);
    }
}
