//! Hostile inputs: bytes and characters a user can't act on without help
//! (invalid UTF-8, invisible and look-alike characters, a misspelled
//! keyword). Each is reported at its line and column, with a hint.

use crate::bound::*;

const HEAD: &str = "coordinates x\nparameters m, k\n";

/// `qdot derive` on `src`: fails cleanly with exactly `expected` on stderr.
#[track_caller]
fn derive_fails_with(tag: &str, src: &[u8], expected: &str) {
    let o = qdot_scene(tag, src, "derive", &[]);
    o.assert_clean();
    assert_eq!(o.code, Some(1), "{o:?}");
    assert_eq!(o.stdout, "", "{o:?}");
    assert_eq!(o.stderr, expected);
}

#[test]
fn invalid_utf8_is_positioned_at_its_first_byte() {
    // `é` in UTF-8 on line 3 (a valid character before the bad byte: the
    // column counts characters), then a Latin-1 `é` (0xE9)
    let mut src = HEAD.as_bytes().to_vec();
    src.extend_from_slice("# café\nkinetic E = 1/2*m*x'^2 # ét".as_bytes());
    src.push(0xE9);
    src.extend_from_slice(b"\npotential V = 1/2*k*x^2 # \xE9\n");
    derive_fails_with(
        "utf8",
        &src,
        "error: the file is not valid UTF-8: byte 0xE9 here\n \
         --> scene.qd:4:28\n  |\n\
         4 | kinetic E = 1/2*m*x'^2 # ét\u{FFFD}\n  \
         |                            ^\n  \
         = hint: save the file as UTF-8 (in Latin-1 or Windows-1252, 0xE9 is `é`)\n",
    );
}

#[test]
fn a_truncated_character_at_the_end_is_positioned() {
    let mut src = HEAD.as_bytes().to_vec();
    src.extend_from_slice(b"y = x\xE2\x82");
    derive_fails_with(
        "truncated",
        &src,
        "error: the file is not valid UTF-8: bytes 0xE2 0x82 here (an incomplete character)\n \
         --> scene.qd:3:6\n  |\n\
         3 | y = x\u{FFFD}\n  \
         |      ^\n  \
         = hint: save the file as UTF-8\n",
    );
}

#[test]
fn invalid_utf8_through_the_repl_load_is_positioned() {
    let mut src = HEAD.as_bytes().to_vec();
    src.extend_from_slice(b"w = 1/2*k\x92s\n");
    let o = qdot_scene("repl_utf8", &src, "repl", &[]);
    o.assert_clean();
    assert_eq!(o.code, Some(1), "{o:?}");
    assert_eq!(
        o.stderr,
        "error: the file is not valid UTF-8: byte 0x92 here\n \
         --> scene.qd:3:10\n  |\n\
         3 | w = 1/2*k\u{FFFD}s\n  \
         |          ^\n  \
         = hint: save the file as UTF-8 (in Latin-1 or Windows-1252, 0x92 is `’`)\n",
    );
}

#[test]
fn a_zero_width_space_is_named_by_its_code_point() {
    let src = format!("{HEAD}kinetic E = 1/2*m*x'^2\npotential V = 1/2*k*x\u{200B}^2\n");
    derive_fails_with(
        "zwsp",
        src.as_bytes(),
        "error: unknown character U+200B (ZERO WIDTH SPACE), which is invisible\n \
         --> scene.qd:4:22\n  |\n\
         4 | potential V = 1/2*k*x\u{FFFD}^2\n  \
         |                      ^\n  \
         = hint: delete it (invisible characters often come with text pasted from a web page or a word processor)\n",
    );
}

#[test]
fn a_right_to_left_override_is_refused_even_in_a_comment() {
    // "Trojan Source": the override makes the comment display as code (on
    // a terminal this line reads `… # V = 1/2*k*x^2 laitnetop`); it is shown
    // as U+FFFD in the echoed line
    let src = format!("{HEAD}kinetic E = 1/2*m*x'^2 # \u{202E}2^x*k*2/1 = V laitnetop\n");
    derive_fails_with(
        "rlo",
        src.as_bytes(),
        "error: invisible character U+202E (RIGHT-TO-LEFT OVERRIDE), which reorders how the line is displayed\n \
         --> scene.qd:3:26\n  |\n\
         3 | kinetic E = 1/2*m*x'^2 # \u{FFFD}2^x*k*2/1 = V laitnetop\n  \
         |                          ^\n  \
         = hint: delete it: with it the text shown is not the text read (it is refused in comments and strings too)\n",
    );
}

#[test]
fn a_greek_question_mark_is_not_a_semicolon() {
    let src = format!("{HEAD}kinetic E = 1/2*m*x'^2\u{37E} potential V = 1/2*k*x^2\n");
    derive_fails_with(
        "greekq",
        src.as_bytes(),
        "error: unknown character U+037E (GREEK QUESTION MARK), which looks like `;`\n \
         --> scene.qd:3:23\n  |\n\
         3 | kinetic E = 1/2*m*x'^2\u{37E} potential V = 1/2*k*x^2\n  \
         |                       ^\n  \
         = hint: replace it with the ASCII `;`\n",
    );
}

#[test]
fn a_cyrillic_letter_in_a_latin_name_is_refused_at_that_letter() {
    // `mаss` with a Cyrillic а: without the check, `mass` below would be
    // an unknown name that looks exactly like the declared one
    let src = "coordinates x\nparameters m\u{430}ss, k\nkinetic E = 1/2*mass*x'^2\n";
    derive_fails_with(
        "cyrillic",
        src.as_bytes(),
        "error: the name `m\u{430}ss` has the character U+0430 (CYRILLIC SMALL LETTER A), which looks like `a`\n \
         --> scene.qd:2:13\n  |\n\
         2 | parameters m\u{430}ss, k\n  \
         |             ^\n  \
         = hint: retype it as the ASCII `a`: a name spelled with a look-alike letter is another name, though it looks the same\n",
    );
}

#[test]
fn names_in_other_scripts_and_a_no_break_space_are_fine() {
    let src = "coordinates θ3\nparameters масса, k\nkinetic E = 1/2*масса*θ3'^2\npotential V =\u{A0}1/2*k*θ3^2\n";
    let o = qdot_scene("scripts", src.as_bytes(), "solve", &[]);
    o.assert_clean();
    assert_eq!(o.code, Some(0), "{o:?}");
    assert!(o.stdout.contains("θ̈₃ = −k/масса·θ₃"), "{}", o.stdout);
}

#[test]
fn a_misspelled_keyword_gets_did_you_mean() {
    let src = format!("{HEAD}kinetic E = 1/2*m*x'^2\npotental V = 1/2*k*x^2\n");
    derive_fails_with(
        "keyword",
        src.as_bytes(),
        "error: unknown keyword `potental`\n \
         --> scene.qd:4:1\n  |\n\
         4 | potental V = 1/2*k*x^2\n  \
         | ^^^^^^^^\n  \
         = hint: did you mean `potential`?\n",
    );
    let src = "coordinate x\nparameters m\nkinetic E = 1/2*m*x'^2\n";
    let o = qdot_scene("keyword2", src.as_bytes(), "derive", &[]);
    o.assert_clean();
    assert!(
        o.stderr
            .starts_with("error: unknown keyword `coordinate`\n --> scene.qd:1:1\n"),
        "{o:?}"
    );
    assert!(
        o.stderr.ends_with("= hint: did you mean `coordinates`?\n"),
        "{o:?}"
    );
}
