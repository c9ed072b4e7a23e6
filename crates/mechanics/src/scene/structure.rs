//! Reading a scene expanded or with its kinematics kept (`--expand`,
//! `--structured`, and the size rule between them), for every command
//! that can write or compile its results through intermediates.

use super::Scene;
use crate::diag::Diagnostic;

/// Whether results are written expanded or through named intermediates
/// ([`crate::expr::tape`]).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[non_exhaustive]
pub enum Structure {
    /// Expanded where that stays small: a scene with bodies is kept when
    /// the expanded M and f of its structured derivation pass
    /// [`crate::limits::STRUCTURE_ABOVE_TERMS`] terms.
    #[default]
    Auto,
    /// Always expanded (`--expand`): the canonical form throughout.
    Expanded,
    /// Always through intermediates where the scene allows it
    /// (`--structured`).
    Kept,
}

impl Scene {
    /// The scene of `src`, read as `structure` asks. `Auto` keeps the
    /// kinematics of a scene with bodies when it allows it and the
    /// expanded M and f of its structured derivation would pass
    /// [`crate::limits::STRUCTURE_ABOVE_TERMS`] terms; otherwise (and for
    /// every scene it cannot keep) it reads the scene expanded, so small
    /// scenes come out exactly as they always have.
    pub fn read(src: &str, structure: Structure) -> Result<Scene, Diagnostic> {
        Scene::read_keeping(src, structure, &[])
    }

    /// [`Scene::read`] with the definitions `keep` kept as intermediates
    /// (`--keep`): a scene read so is always structured
    /// ([`Scene::parse_keeping`]).
    pub fn read_keeping(
        src: &str,
        structure: Structure,
        keep: &[String],
    ) -> Result<Scene, Diagnostic> {
        crate::diag::bounded(|| {
            if !keep.is_empty() {
                return Scene::parse_keeping(src, keep);
            }
            match structure {
                Structure::Expanded => Scene::parse(src),
                Structure::Kept => Scene::parse_structured(src),
                Structure::Auto if !has_bodies(src) => Scene::parse(src),
                Structure::Auto => match Scene::parse_structured(src) {
                    Ok(kept) if worth_keeping(&kept) => Ok(kept),
                    _ => Scene::parse(src),
                },
            }
        })
    }
}

/// Whether the scene has `body` or `particle` statements, the scenes whose
/// kinematics can grow past the rule (the others are read once, expanded).
fn has_bodies(src: &str) -> bool {
    // without either keyword in the text there is no such statement, and
    // the source is parsed once, not twice
    if !src.contains("body") && !src.contains("particle") {
        return false;
    }
    crate::parse::parse_scene(src).is_ok_and(|stmts| {
        stmts
            .iter()
            .any(|s| matches!(s, crate::parse::ast::Stmt::Body(_)))
    })
}

/// Whether a structured scene's equations expand past the size rule. The
/// expansion is measured under a budget just above the rule, so a large
/// scene costs little to tell.
fn worth_keeping(scene: &Scene) -> bool {
    let Some(tape) = scene.tape.as_ref().filter(|t| !t.is_empty()) else {
        return false;
    };
    // `solve` blocks are kept only on request (`--keep`, `--structured`)
    if !scene.has_dynamics() || !scene.systems.is_empty() {
        return false;
    }
    let limit = crate::limits::STRUCTURE_ABOVE_TERMS;
    let measured = crate::budget::probe(limit.saturating_mul(16), || {
        let Ok(l) = scene.lagrange() else {
            return None;
        };
        let tape = l.intermediates.as_deref().unwrap_or(tape);
        let mut terms = 0usize;
        for e in l.mass_matrix.iter().flatten().chain(&l.forcing) {
            let x = tape.expand(e).ok()?;
            terms += x.num().len() + x.den().len();
            if terms > limit {
                return Some(true);
            }
        }
        Some(false)
    });
    match measured {
        Ok(Some(keep)) => keep,
        // a derivation that fails is reported by the expanded reading
        Ok(None) => false,
        // past the measuring budget: far past the rule
        Err(_) => true,
    }
}
