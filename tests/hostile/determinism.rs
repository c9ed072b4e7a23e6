//! Output that depended on what the process read before: a REPL session
//! (or a Python one) prints a scene as a fresh process does, whatever
//! scenes it read first.

use crate::bound::*;

/// The last non-empty line the REPL printed for `session`.
fn last_line(session: &str) -> String {
    let o = qdot_bounded(&["repl"], session, SECONDS, MEMORY_MIB);
    o.assert_clean();
    assert_eq!(o.code, Some(0), "{o:?}");
    o.stdout
        .lines()
        .map(str::trim)
        .rfind(|l| !l.is_empty())
        .unwrap_or_default()
        .to_string()
}

#[test]
fn an_argument_prints_in_the_order_of_the_scene_in_force() {
    // the text of sin(2·x − 2·y) was kept from a scene with `y` first
    let session = "coordinates x, y\n:reset\ncoordinates y, x\nsin(2*x-2*y)\n\
                   :reset\ncoordinates x, y\nsin(2*x-2*y)\n";
    assert_eq!(last_line(session), "sin(2·x − 2·y)");
    assert_eq!(
        last_line("coordinates x, y\nsin(2*x-2*y)\n"),
        "sin(2·x − 2·y)"
    );
}

#[test]
fn a_folded_angle_does_not_follow_the_order_of_first_use() {
    // cos(θ₁ − θ₂) is stored expanded; the earlier scene made sin θ₂'s
    // atom before sin θ₁'s
    let before = "coordinates th2, th1\ncos(th2 - th1)\n:reset\n";
    let now = "coordinates th1, th2\nparameters m\nm*cos(th1-th2)*th1'' + sin(th1-th2)*th2'^2\n";
    let fresh = "m·cos(θ₁ − θ₂)·θ̈₁ + sin(θ₁ − θ₂)·θ̇₂²";
    assert_eq!(last_line(now), fresh);
    assert_eq!(last_line(&format!("{before}{now}")), fresh);
    // a sum of angles follows the declaration, as the sums do, whatever
    // was declared before
    let after = "coordinates y, x\n:reset\ncoordinates x, y\nsin(x + y)\n";
    assert_eq!(last_line(after), "sin(x + y)");
    let after = "coordinates x, y\nx*y\n:reset\ncoordinates y, x\nsin(x + y)\n";
    assert_eq!(last_line(after), "sin(y + x)");
}
