//! The grammar file and the parser stay in step: every rule of
//! `grammar/qd.ebnf` appears as a doc comment "/// `rule ::= body`" in
//! the parser's files (`crates/syntax/src/parse/*.rs`) with the same body (white space
//! aside).

use std::collections::BTreeMap;

fn strip_comments(s: &str) -> String {
    let mut out = String::new();
    let mut rest = s;
    while let Some(a) = rest.find("/*") {
        out.push_str(&rest[..a]);
        let b = rest[a + 2..].find("*/").expect("unterminated comment") + a + 4;
        rest = &rest[b..];
    }
    assert!(!rest.contains("*/"), "stray */");
    out.push_str(rest);
    out
}

fn norm(s: &str) -> String {
    s.split_whitespace().collect::<Vec<_>>().join(" ")
}

/// rule name -> body, from the EBNF.
fn grammar_rules() -> BTreeMap<String, String> {
    let src = std::fs::read_to_string(concat!(env!("QDOT_ROOT"), "/grammar/qd.ebnf")).unwrap();
    let text = strip_comments(&src);
    let mut rules = BTreeMap::new();
    let mut current: Option<(String, String)> = None;
    for line in text.lines() {
        let starts_rule = line
            .split_once("::=")
            .filter(|(name, _)| !line.starts_with(' ') && !name.trim().contains(' '));
        if let Some((name, body)) = starts_rule {
            if let Some((n, b)) = current.take() {
                rules.insert(n, norm(&b));
            }
            current = Some((name.trim().to_string(), body.to_string()));
        } else if let Some((_, b)) = current.as_mut() {
            b.push(' ');
            b.push_str(line);
        }
    }
    if let Some((n, b)) = current {
        rules.insert(n, norm(&b));
    }
    rules
}

/// The parser's source: every file of crates/syntax/src/parse/, in name order.
fn parser_source() -> String {
    let dir = concat!(env!("QDOT_ROOT"), "/crates/syntax/src/parse");
    let mut files: Vec<_> = std::fs::read_dir(dir)
        .expect("crates/syntax/src/parse")
        .map(|e| e.expect("an entry").path())
        .filter(|p| p.extension().is_some_and(|x| x == "rs"))
        .collect();
    files.sort();
    files
        .iter()
        .map(|f| std::fs::read_to_string(f).expect("readable"))
        .collect::<Vec<_>>()
        .join("\n")
}

/// rule name -> body, from the parser's doc comments.
fn parser_rules() -> BTreeMap<String, String> {
    let src = parser_source();
    let mut rules = BTreeMap::new();
    for line in src.lines() {
        let Some(doc) = line.trim().strip_prefix("/// `") else {
            continue;
        };
        let Some((name, rest)) = doc.split_once(" ::= ") else {
            continue;
        };
        let body = rest.split_once('`').map(|(b, _)| b).unwrap_or(rest);
        rules.insert(name.to_string(), norm(body));
    }
    rules
}

#[test]
fn every_rule_has_a_parser_function_with_the_same_body() {
    let grammar = grammar_rules();
    let parser = parser_rules();
    assert!(grammar.len() >= 30, "{grammar:?}");
    // `Letter` and friends are character classes described in comments
    for (name, body) in &grammar {
        let got = parser
            .get(name)
            .unwrap_or_else(|| panic!("no parser doc comment for rule `{name}`"));
        assert_eq!(got, body, "rule `{name}` differs");
    }
    for name in parser.keys() {
        assert!(grammar.contains_key(name), "`{name}` is not in the grammar");
    }
}

#[test]
fn rule_functions_are_named_after_rules() {
    let src = parser_source();
    for name in grammar_rules().keys() {
        let needle = format!("fn {name}(");
        assert!(src.contains(&needle), "no function `{name}`");
    }
}

#[test]
fn latex_statement_and_string_are_live_rules() {
    let grammar = grammar_rules();
    for rule in ["latex_stmt", "string"] {
        assert!(grammar.contains_key(rule), "no live rule `{rule}`");
    }
    let statement: Vec<String> = grammar["statement"]
        .split('|')
        .map(|a| a.trim().to_string())
        .collect();
    assert!(statement.iter().any(|a| a == "latex_stmt"), "{statement:?}");
}

#[test]
fn statements_vectors_and_solve_blocks_are_live_rules() {
    let grammar = grammar_rules();
    for rule in [
        "load_stmt",
        "torque_stmt",
        "solve_block",
        "block_ws",
        "equation",
        "vector",
    ] {
        assert!(grammar.contains_key(rule), "no live rule `{rule}`");
    }
    // each new statement is an alternative of `statement`, each new atom of `atom`
    let alternatives = |rule: &str| -> Vec<String> {
        grammar[rule]
            .split('|')
            .map(|a| a.trim().to_string())
            .collect()
    };
    let statement = alternatives("statement");
    for alt in ["load_stmt", "torque_stmt", "solve_block"] {
        assert!(
            statement.iter().any(|a| a == alt),
            "{statement:?} lacks {alt}"
        );
    }
    assert_eq!(statement.last().map(String::as_str), Some("definition"));
    assert!(alternatives("atom").iter().any(|a| a == "vector"));
    // the grammar states the stop-word rule of `load`/`torque`
    let src = std::fs::read_to_string(concat!(env!("QDOT_ROOT"), "/grammar/qd.ebnf")).unwrap();
    assert!(src.contains("Stop word"), "stop-word rule missing");
    assert!(src.contains("[x, y]"));
}
