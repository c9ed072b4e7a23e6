//! `qdot cycle --animate FILE.html` (or `.svg`): the mechanism drawn from
//! its bodies and joints at every row of the cycle, moving in a loop.
//!
//! The geometry is computed here once, for both outputs: every moving
//! element of the drawing has one attribute per row (a polygon's
//! `points`, a circle's centre, a group's translation or rotation). The
//! HTML page embeds those values with the table as JSON and a small
//! player (play/pause, a slider to scrub, the row's reactions as text);
//! the SVG gives each attribute an SMIL `<animate>` through the same
//! values. Both are self-contained: no font, script or style is fetched.

use super::plot::acting;
use crate::cycle::{CycleRow, CycleTable, JointKind};
use crate::drawing::style::PALETTE;
use crate::simulate::plot::pretty_column as pretty;
use serde_json::{json, Value};
use std::fmt::Write;

/// The view's longer side in SVG units: the mechanism is scaled to it,
/// so every size below is in these units whatever the scene's are.
const VIEW: f64 = 1000.0;
/// A link's bar, a pin's radius, a block's width and height, a label's
/// size.
const BAR: f64 = 16.0;
const PIN: f64 = 9.0;
const BLOCK: (f64, f64) = (72.0, 46.0);
const FONT: f64 = 26.0;
/// How far a guide's line reaches either way from its point: across any
/// view.
const REACH: f64 = 2.0 * VIEW;

/// The scene's coordinates mapped onto the view: x to the right, y up,
/// every row's points inside with a margin.
struct View {
    x0: f64,
    y1: f64,
    scale: f64,
    width: f64,
    height: f64,
}

impl View {
    /// The view around every finite point of every row.
    fn around(rows: &[CycleRow]) -> View {
        let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
        for p in rows.iter().flat_map(|r| &r.points) {
            if p.iter().all(|v| v.is_finite()) {
                for i in 0..2 {
                    lo[i] = lo[i].min(p[i]);
                    hi[i] = hi[i].max(p[i]);
                }
            }
        }
        if !lo[0].is_finite() {
            (lo, hi) = ([-1.0; 2], [1.0; 2]);
        }
        let size = (hi[0] - lo[0]).max(hi[1] - lo[1]);
        let size = if size > 0.0 { size } else { 1.0 };
        // room for the supports, blocks and labels; and never a strip
        // flatter than 2 : 5
        let pad = 0.16 * size;
        let (mut w, mut h) = (hi[0] - lo[0] + 2.0 * pad, hi[1] - lo[1] + 2.0 * pad);
        let (cx, cy) = ((lo[0] + hi[0]) / 2.0, (lo[1] + hi[1]) / 2.0);
        w = w.max(0.4 * h);
        h = h.max(0.4 * w);
        let scale = VIEW / w.max(h);
        View {
            x0: cx - w / 2.0,
            y1: cy + h / 2.0,
            scale,
            width: w * scale,
            height: h * scale,
        }
    }

    fn map(&self, p: [f64; 2]) -> (f64, f64) {
        ((p[0] - self.x0) * self.scale, (self.y1 - p[1]) * self.scale)
    }
}

/// An SVG number: one decimal in the view's units (a tenth of a pixel on
/// a 1000-pixel picture), never `-0.0`.
fn num(v: f64) -> String {
    let s = format!("{v:.1}");
    if s == "-0.0" {
        "0.0".into()
    } else {
        s
    }
}

/// Text for HTML or XML: `&`, `<`, `>` and quotes escaped.
fn escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

/// A palette colour as CSS.
fn hex(c: plotters::style::RGBColor) -> String {
    format!("#{:02x}{:02x}{:02x}", c.0, c.1, c.2)
}

/// The drawing: its elements at the first row, and every moving
/// attribute's value at every row.
struct Figure {
    view: View,
    /// The SVG elements (definitions and shapes), drawn at the first row.
    elements: String,
    moving: Moving,
}

/// The drawing's moving attributes.
#[derive(Default)]
struct Moving {
    /// Each one: an element's id and `points`, `cx`, `cy`, `x`, `y`,
    /// `opacity`, `translate` or `rotate` (the last two: the group's
    /// `transform`).
    targets: Vec<(String, &'static str)>,
    /// Per target, its value at every row.
    values: Vec<Vec<String>>,
}

impl Moving {
    /// A moving attribute with its values; its value at the first row.
    fn add(&mut self, id: &str, attr: &'static str, values: Vec<String>) -> String {
        let first = values.first().cloned().unwrap_or_default();
        self.targets.push((id.to_string(), attr));
        self.values.push(values);
        first
    }
}

/// The points of every row on the view.
struct Points<'a> {
    table: &'a CycleTable,
    view: &'a View,
    /// The row whose points draw each row ([`drawable_rows`]).
    source: Vec<usize>,
}

impl Points<'_> {
    /// Point `i` at row `k`, on the view.
    fn at(&self, k: usize, i: usize) -> (f64, f64) {
        self.view.map(self.table.rows[self.source[k]].points[i])
    }

    /// Point `i` at every row.
    fn track(&self, i: usize) -> Vec<(f64, f64)> {
        (0..self.source.len()).map(|k| self.at(k, i)).collect()
    }

    /// Point `i` at every row, as a translation `x,y`.
    fn translate(&self, i: usize) -> Vec<String> {
        self.track(i)
            .into_iter()
            .map(|(x, y)| format!("{},{}", num(x), num(y)))
            .collect()
    }

    /// How far along guide `g` point `i` goes at the least and at the
    /// most over the rows, from the guide's point, on the view.
    fn stroke(&self, g: [usize; 2], i: usize) -> (f64, f64) {
        (0..self.source.len())
            .map(|k| {
                let (p, q, x) = (self.at(k, g[0]), self.at(k, g[1]), self.at(k, i));
                let (ux, uy) = (q.0 - p.0, q.1 - p.1);
                ((x.0 - p.0) * ux + (x.1 - p.1) * uy) / ux.hypot(uy).max(1e-300)
            })
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), s| {
                (lo.min(s), hi.max(s))
            })
    }

    /// Where a pin's name goes at row `k`: the unit direction away from
    /// the links meeting at its point `i` (a grounded pin's: to the side,
    /// its support is below), and how far (past a block on the pin).
    fn label_side(&self, k: usize, i: usize, grounded: bool) -> (f64, f64, f64) {
        let p = self.at(k, i);
        let near = |q: (f64, f64)| (q.0 - p.0).hypot(q.1 - p.1) < 1.0;
        let (mut sx, mut sy, mut block) = (0.0, 0.0, false);
        for body in &self.table.drawing.bodies {
            let at: Vec<(f64, f64)> = body.points.iter().map(|&j| self.at(k, j)).collect();
            if !at.iter().any(|&q| near(q)) {
                continue;
            }
            let others: Vec<&(f64, f64)> = at.iter().filter(|&&q| !near(q)).collect();
            block |= body.particle || others.is_empty();
            for q in others {
                let (dx, dy) = (q.0 - p.0, q.1 - p.1);
                let d = dx.hypot(dy);
                sx += dx / d;
                sy += dy / d;
            }
        }
        let far = if block {
            BLOCK.0 / 2.0 + 16.0
        } else {
            PIN + 20.0
        };
        let (ux, uy) = if block {
            // above the block's corner: a block sits on its rail
            (1.0, -0.8)
        } else if grounded {
            (if sx > 0.0 { -1.0 } else { 1.0 }, -0.5)
        } else if sx.hypot(sy) < 0.3 {
            (1.0, -1.0)
        } else {
            (-sx, -sy)
        };
        let d = ux.hypot(uy);
        (ux / d, uy / d, far)
    }

    /// A guide's direction at every row, as the SVG rotation in degrees
    /// (clockwise: the view's y points down).
    fn rotate(&self, g: [usize; 2]) -> Vec<String> {
        let angles = (0..self.source.len())
            .map(|k| {
                let (p, q) = (self.at(k, g[0]), self.at(k, g[1]));
                (q.1 - p.1).atan2(q.0 - p.0).to_degrees()
            })
            .collect();
        unwrapped(angles).into_iter().map(num).collect()
    }
}

/// The rows whose points draw each row: itself when all its points are
/// finite, else the nearest earlier such row (the first such for the
/// leading ones). `None` when no row has finite points.
fn drawable_rows(table: &CycleTable) -> Option<Vec<usize>> {
    let needed = table
        .drawing
        .bodies
        .iter()
        .flat_map(|b| b.points.iter().copied())
        .chain(
            table
                .drawing
                .joints
                .iter()
                .flat_map(|j| std::iter::once(j.point).chain(j.guide.into_iter().flatten())),
        )
        .max();
    let good = |r: &CycleRow| {
        needed.is_none_or(|n| n < r.points.len())
            && r.points.iter().flatten().all(|v| v.is_finite())
    };
    let first = table.rows.iter().position(good)?;
    let mut last = first;
    Some(
        table
            .rows
            .iter()
            .enumerate()
            .map(|(k, r)| {
                if good(r) {
                    last = k;
                }
                last
            })
            .collect(),
    )
}

/// The indices of a body's points around its convex hull at one row (a
/// rigid body keeps it): two for a bar, one when all coincide.
fn hull(points: &[usize], at: &[[f64; 2]]) -> Vec<usize> {
    let size = points
        .iter()
        .flat_map(|&i| at[i].map(f64::abs))
        .fold(0.0, f64::max);
    let eps = 1e-9 * size.max(1e-300);
    let mut ps: Vec<usize> = points.to_vec();
    ps.sort_by(|&a, &b| {
        at[a][0]
            .total_cmp(&at[b][0])
            .then(at[a][1].total_cmp(&at[b][1]))
    });
    ps.dedup_by(|a, b| {
        (at[*a][0] - at[*b][0]).abs() <= eps && (at[*a][1] - at[*b][1]).abs() <= eps
    });
    if ps.len() < 3 {
        return ps;
    }
    let cross = |o: usize, a: usize, b: usize| {
        (at[a][0] - at[o][0]) * (at[b][1] - at[o][1])
            - (at[a][1] - at[o][1]) * (at[b][0] - at[o][0])
    };
    // Andrew's monotone chain, collinear points dropped
    let mut lower: Vec<usize> = Vec::new();
    for &p in &ps {
        while lower.len() >= 2
            && cross(lower[lower.len() - 2], lower[lower.len() - 1], p) <= eps * eps
        {
            lower.pop();
        }
        lower.push(p);
    }
    let mut upper: Vec<usize> = Vec::new();
    for &p in ps.iter().rev() {
        while upper.len() >= 2
            && cross(upper[upper.len() - 2], upper[upper.len() - 1], p) <= eps * eps
        {
            upper.pop();
        }
        upper.push(p);
    }
    lower.pop();
    upper.pop();
    lower.extend(upper);
    lower
}

/// Angles in degrees made continuous from row to row (no turn of 360°
/// between neighbours), so an interpolated rotation never spins back.
fn unwrapped(mut degrees: Vec<f64>) -> Vec<f64> {
    for k in 1..degrees.len() {
        let turn = ((degrees[k] - degrees[k - 1]) / 360.0).round();
        degrees[k] -= 360.0 * turn;
    }
    degrees
}

/// The mechanism's drawing over the table's rows.
fn figure(table: &CycleTable) -> Figure {
    let view = View::around(&table.rows);
    let mut elements = defs();
    let mut moving = Moving::default();
    if let Some(source) = drawable_rows(table) {
        let points = Points {
            table,
            view: &view,
            source,
        };
        // guides and supports first: the links move over them
        grounds(&points, &mut moving, &mut elements);
        bodies(&points, &mut moving, &mut elements);
        forces(&points, &mut moving, &mut elements);
        joints(&points, &mut moving, &mut elements);
    }
    Figure {
        view,
        elements,
        moving,
    }
}

/// Every slider's guide (hatched when grounded) and every grounded pin's
/// support.
fn grounds(points: &Points, moving: &mut Moving, out: &mut String) {
    for (j, joint) in points.table.drawing.joints.iter().enumerate() {
        if let Some(g) = joint.guide {
            let (id, rid) = (format!("j{j}g"), format!("j{j}gr"));
            let t = moving.add(&id, "translate", points.translate(g[0]));
            let r = moving.add(&rid, "rotate", points.rotate(g));
            let _ = write!(
                out,
                "<g id=\"{id}\" transform=\"translate({t})\"><g id=\"{rid}\" transform=\"rotate({r})\">"
            );
            if joint.grounded {
                // the rail under the block (on the side of the guide's
                // direction turned −90°), as long as the block's stroke
                let (from, to) = points.stroke(g, joint.point);
                let (from, to) = (from - BLOCK.0, to + BLOCK.0);
                let y = BLOCK.1 / 2.0;
                let _ = write!(
                    out,
                    "<rect x=\"{x}\" y=\"{y}\" width=\"{w}\" height=\"14\" fill=\"url(#hatch)\"/>\
                     <line x1=\"{x}\" y1=\"{y}\" x2=\"{x2}\" y2=\"{y}\" class=\"rail\"/>",
                    x = num(from),
                    w = num(to - from),
                    x2 = num(to),
                );
            }
            let _ = write!(
                out,
                "<line x1=\"{}\" y1=\"0\" x2=\"{REACH}\" y2=\"0\" class=\"guide\"/></g></g>",
                -REACH
            );
        } else if joint.grounded {
            let id = format!("j{j}s");
            let t = moving.add(&id, "translate", points.translate(joint.point));
            let _ = write!(
                out,
                "<g id=\"{id}\" transform=\"translate({t})\" class=\"support\">\
                 <rect x=\"-36\" y=\"38\" width=\"72\" height=\"14\" fill=\"url(#hatch)\" stroke=\"none\"/>\
                 <path d=\"M0 0 L-22 38 L22 38 Z M-36 38 H36\"/></g>"
            );
        }
    }
}

/// Every body: a rigid body as the polygon around its points (a bar
/// for two) with its centre of mass; a particle, or a body whose points
/// all coincide, as a block turned with its guide.
fn bodies(points: &Points, moving: &mut Moving, out: &mut String) {
    let d = &points.table.drawing;
    let first = &points.table.rows[points.source[0]].points;
    for (b, body) in d.bodies.iter().enumerate() {
        let colour = hex(PALETTE[b % PALETTE.len()]);
        let Some(&centre) = body.points.first() else {
            continue;
        };
        let around = hull(&body.points, first);
        if body.particle || around.len() < 2 {
            let (id, rid) = (format!("b{b}k"), format!("b{b}kr"));
            let t = moving.add(&id, "translate", points.translate(centre));
            let guide = d
                .joints
                .iter()
                .filter(|j| body.points.contains(&j.point))
                .find_map(|j| j.guide);
            let r = match guide {
                Some(g) => moving.add(&rid, "rotate", points.rotate(g)),
                None => "0".into(),
            };
            let _ = write!(
                out,
                "<g id=\"{id}\" transform=\"translate({t})\"><g id=\"{rid}\" transform=\"rotate({r})\">\
                 <rect x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\" rx=\"4\" fill=\"{colour}\" class=\"block\"/></g></g>",
                -BLOCK.0 / 2.0,
                -BLOCK.1 / 2.0,
                BLOCK.0,
                BLOCK.1
            );
            continue;
        }
        let id = format!("b{b}");
        let polygon: Vec<String> = (0..points.source.len())
            .map(|k| {
                let corners: Vec<String> = around
                    .iter()
                    .map(|&i| {
                        let (x, y) = points.at(k, i);
                        format!("{},{}", num(x), num(y))
                    })
                    .collect();
                corners.join(" ")
            })
            .collect();
        let p = moving.add(&id, "points", polygon);
        let _ = write!(
            out,
            "<polygon id=\"{id}\" points=\"{p}\" stroke=\"{colour}\" fill=\"{colour}\" class=\"link\"/>"
        );
        let cid = format!("b{b}c");
        let (xs, ys): (Vec<String>, Vec<String>) = points
            .track(centre)
            .into_iter()
            .map(|(x, y)| (num(x), num(y)))
            .unzip();
        let cx = moving.add(&cid, "cx", xs);
        let cy = moving.add(&cid, "cy", ys);
        let _ = write!(
            out,
            "<circle id=\"{cid}\" cx=\"{cx}\" cy=\"{cy}\" r=\"5\" class=\"centre\"/>"
        );
    }
}

/// Each joint's reaction at each row (the force on its second body, in
/// the view's directions: y down), where the row has it.
fn reaction(table: &CycleTable, points: &Points, joint: usize, k: usize) -> Option<(f64, f64)> {
    let drawn = &table.drawing.joints[joint];
    let columns = &table.joints.iter().find(|j| j.name == drawn.name)?.columns;
    let value = |c: usize| table.rows[k].values.get(c).copied().flatten();
    let (fx, fy) = match (drawn.kind, drawn.guide) {
        (JointKind::Pin, _) => (value(*columns.first()?)?, -value(*columns.get(1)?)?),
        (JointKind::Slider, Some(g)) => {
            // across the guide: its direction turned +90° (−90° on the view)
            let n = value(*columns.first()?)?;
            let (p, q) = (points.at(k, g[0]), points.at(k, g[1]));
            let (a, b) = (q.0 - p.0, q.1 - p.1);
            let d = a.hypot(b);
            (n * b / d, -n * a / d)
        }
        (JointKind::Slider, None) => return None,
    };
    (fx.is_finite() && fy.is_finite()).then_some((fx, fy))
}

/// Every joint's reaction as an arrow from its point, all to one scale
/// (the largest over the cycle a fifth of the view); hidden where a row
/// has none.
fn forces(points: &Points, moving: &mut Moving, out: &mut String) {
    let table = points.table;
    let rows = points.source.len();
    let all: Vec<Vec<Option<(f64, f64)>>> = (0..table.drawing.joints.len())
        .map(|j| (0..rows).map(|k| reaction(table, points, j, k)).collect())
        .collect();
    let largest = all
        .iter()
        .flatten()
        .flatten()
        .map(|f| f.0.hypot(f.1))
        .fold(0.0, f64::max);
    if largest <= 0.0 {
        return;
    }
    let scale = 0.2 * VIEW / largest;
    let _ = write!(out, "<g class=\"forces\">");
    for (j, joint) in table.drawing.joints.iter().enumerate() {
        if all[j].iter().all(Option::is_none) {
            continue;
        }
        let (arrows, shown): (Vec<String>, Vec<String>) = (0..rows)
            .map(|k| {
                let (x, y) = points.at(k, joint.point);
                let (fx, fy) = all[j][k].unwrap_or((0.0, 0.0));
                let (dx, dy) = (fx * scale, fy * scale);
                // too short for its head: hidden
                let visible = all[j][k].is_some() && dx.hypot(dy) >= 4.0;
                let line = format!("{},{} {},{}", num(x), num(y), num(x + dx), num(y + dy));
                (line, if visible { "1" } else { "0" }.to_string())
            })
            .unzip();
        let id = format!("j{j}f");
        let p = moving.add(&id, "points", arrows);
        let o = moving.add(&id, "opacity", shown);
        let _ = write!(
            out,
            "<polyline id=\"{id}\" points=\"{p}\" opacity=\"{o}\" class=\"force\" marker-end=\"url(#arrow)\"/>"
        );
    }
    out.push_str("</g>");
}

/// Every pin as a circle, and every joint's name beside it.
fn joints(points: &Points, moving: &mut Moving, out: &mut String) {
    for (j, joint) in points.table.drawing.joints.iter().enumerate() {
        let (xs, ys): (Vec<f64>, Vec<f64>) = points.track(joint.point).into_iter().unzip();
        if joint.kind == JointKind::Pin {
            let id = format!("j{j}p");
            let cx = moving.add(&id, "cx", xs.iter().copied().map(num).collect());
            let cy = moving.add(&id, "cy", ys.iter().copied().map(num).collect());
            let _ = write!(
                out,
                "<circle id=\"{id}\" cx=\"{cx}\" cy=\"{cy}\" r=\"{PIN}\" class=\"pin\"/>"
            );
        }
        // a pin's name away from the links meeting there; a slider's
        // above its block's left corner, clear of a pin on the block
        let id = format!("j{j}t");
        let (lx, ly, anchor): (Vec<String>, Vec<String>, &str) = match joint.kind {
            JointKind::Pin => {
                let (lx, ly) = (0..points.source.len())
                    .map(|k| {
                        let (ux, uy, far) = points.label_side(k, joint.point, joint.grounded);
                        (num(xs[k] + far * ux), num(ys[k] + far * uy))
                    })
                    .unzip();
                (lx, ly, "middle")
            }
            JointKind::Slider => {
                let (dx, dy) = (-BLOCK.0 / 2.0 - 4.0, -BLOCK.1 / 2.0 - 18.0);
                let lx = xs.iter().map(|x| num(x + dx)).collect();
                let ly = ys.iter().map(|y| num(y + dy)).collect();
                (lx, ly, "end")
            }
        };
        let x = moving.add(&id, "x", lx);
        let y = moving.add(&id, "y", ly);
        let _ = write!(
            out,
            "<text id=\"{id}\" x=\"{x}\" y=\"{y}\" text-anchor=\"{anchor}\" dominant-baseline=\"central\" class=\"label\">{}</text>",
            escape(&pretty(&joint.name))
        );
    }
}

/// The hatching of the ground and the drawing's styles, inside the SVG
/// so that the standalone SVG looks as the page does.
fn defs() -> String {
    format!(
        "<defs><pattern id=\"hatch\" width=\"10\" height=\"10\" patternUnits=\"userSpaceOnUse\" \
         patternTransform=\"rotate(45)\"><line x1=\"0\" y1=\"0\" x2=\"0\" y2=\"10\" stroke=\"#555\" \
         stroke-width=\"2.5\"/></pattern><marker id=\"arrow\" viewBox=\"0 0 10 10\" refX=\"9\" refY=\"5\" \
         markerUnits=\"userSpaceOnUse\" markerWidth=\"22\" markerHeight=\"22\" orient=\"auto\">\
         <path d=\"M0 1 L10 5 L0 9 Z\" fill=\"#6a1b9a\"/></marker></defs><style>\
         .link{{stroke-width:{BAR};stroke-linejoin:round;stroke-linecap:round;fill-opacity:0.3}}\
         .block{{stroke:#222;stroke-width:3}}\
         .pin{{fill:#fff;stroke:#222;stroke-width:3.5}}\
         .centre{{fill:#222}}\
         .support{{fill:#fff;stroke:#222;stroke-width:3;stroke-linejoin:round}}\
         .rail{{stroke:#222;stroke-width:3}}\
         .force{{stroke:#6a1b9a;stroke-width:4;fill:none}}\
         .guide{{stroke:#777;stroke-width:2;stroke-dasharray:26 8 4 8}}\
         .label{{font:bold {FONT}px sans-serif;fill:#111;stroke:#fff;stroke-width:6;\
         paint-order:stroke;stroke-linejoin:round}}</style>"
    )
}

/// How long one loop through the rows takes, in seconds: about 60 ms a
/// row, between 2 s and 8 s (a long table then skips rows).
fn loop_seconds(rows: usize) -> f64 {
    (rows as f64 * 0.06).clamp(2.0, 8.0)
}

/// What the page embeds: the table's names and values, and the drawing's
/// moving attributes row by row (`frames[k][i]`: target i at row k).
fn data(table: &CycleTable, title: &str, degrees: bool, moving: &Moving) -> Value {
    let rows: Vec<Value> = table
        .rows
        .iter()
        .map(|r| json!({ "values": r.values, "note": r.note }))
        .collect();
    let frames: Vec<Vec<&str>> = (0..table.rows.len())
        .map(|k| moving.values.iter().map(|v| v[k].as_str()).collect())
        .collect();
    let joints: Vec<Value> = table
        .joints
        .iter()
        .map(|j| {
            let (on, from) = acting(&j.bodies);
            json!({ "name": pretty(&j.name), "on": on, "from": from, "columns": j.columns })
        })
        .collect();
    let drives: Vec<Value> = table
        .drives
        .iter()
        .map(|d| json!({ "name": pretty(&d.name), "coordinate": pretty(&d.coordinate), "column": d.column }))
        .collect();
    json!({
        "title": title,
        "varied": pretty(&table.varied),
        "degrees": degrees,
        "seconds": loop_seconds(table.rows.len()),
        "columns": table.columns,
        "labels": table.columns.iter().map(|c| pretty(c)).collect::<Vec<_>>(),
        "joints": joints,
        "drives": drives,
        "rows": rows,
        "targets": moving.targets,
        "frames": frames,
    })
}

/// JSON safe inside a `<script>` element: `<`, `>` and `&` (which JSON
/// has only inside strings) as `\u` escapes, so no `</script>` or `<!--`
/// in a name or a note can end or bend the element.
fn script_json(v: &Value) -> String {
    v.to_string()
        .replace('<', "\\u003c")
        .replace('>', "\\u003e")
        .replace('&', "\\u0026")
}

/// The page's styles.
const PAGE_STYLE: &str = "\
body{font:16px/1.45 system-ui,-apple-system,'Segoe UI',sans-serif;margin:18px 26px;color:#111;background:#fff}
h1{font-size:22px;margin:0 0 12px}
.layout{display:flex;gap:28px;align-items:flex-start;flex-wrap:wrap}
.stage{flex:1 1 560px;max-width:980px}
#mechanism{display:block;width:100%;height:auto;max-height:74vh;border:1px solid #ccc;border-radius:6px;background:#fcfcfc}
#mechanism.noted{border-color:#d4a200;box-shadow:0 0 0 2px #f3d36b}
label{white-space:nowrap;color:#333}
.controls{display:flex;gap:14px;align-items:center;margin-top:10px}
.controls input{flex:1}
button{font:inherit;padding:4px 16px;min-width:92px;cursor:pointer}
#position{font-variant-numeric:tabular-nums;color:#444;min-width:9em;text-align:right}
aside{flex:0 0 300px}
#varied{font-size:28px;font-weight:600;font-variant-numeric:tabular-nums}
#note{margin:8px 0;padding:6px 10px;background:#fff3cd;border:1px solid #d4a200;border-radius:4px}
table{border-collapse:collapse;font-variant-numeric:tabular-nums;margin-top:10px;width:100%}
th,td{padding:3px 8px;border-bottom:1px solid #eee}
th{text-align:left;font-weight:normal}
td{text-align:right}
tr.joint th{font-weight:600;padding-top:10px;border-bottom:1px solid #bbb}
.hint{color:#555;font-size:13px}
.legend span{display:inline-block;margin-right:14px}
.swatch{display:inline-block;width:14px;height:14px;border-radius:3px;margin-right:5px;vertical-align:-2px}
";

/// The page's player: shows a row (the drawing's attributes, the
/// position, the note, the reactions), and loops through the rows.
const PLAYER: &str = r#"(() => {
"use strict";
const data = JSON.parse(document.getElementById("cycle-data").textContent);
const n = data.rows.length;
const $ = (id) => document.getElementById(id);
const play = $("play"), scrub = $("scrub"), position = $("position");
const varied = $("varied"), note = $("note"), tbody = $("reactions").tBodies[0];
const targets = data.targets.map(([id, attr]) => [$(id), attr]);
const svg = $("mechanism"), arrows = svg.querySelector(".forces"), showForces = $("forces");
if (arrows) showForces.addEventListener("change", () => arrows.setAttribute("display", showForces.checked ? "inline" : "none"));
else showForces.parentElement.hidden = true;
const cells = [];
function line(label, column, cls) {
  const tr = tbody.insertRow();
  const th = document.createElement("th");
  th.textContent = label;
  tr.appendChild(th);
  if (cls) tr.className = cls;
  if (column !== null) { const td = tr.insertCell(); cells.push([td, column]); } else th.colSpan = 2;
}
for (const j of data.joints) {
  line(`${j.name}: on ${j.on} from ${j.from}`, null, "joint");
  for (const c of j.columns) line(data.labels[c], c);
}
if (data.drives.length) line("drives", null, "joint");
for (const d of data.drives) line(`${d.name} (along ${d.coordinate})`, d.column);
function fmt(v) {
  if (v === null) return "\u2014";
  const a = Math.abs(v);
  if (a === 0) return "0";
  if (a >= 1e-3 && a < 1e6) return String(Number(v.toPrecision(4)));
  return v.toExponential(3);
}
function variedText(v) {
  if (v === null) return `${data.varied} = \u2014`;
  return data.degrees ? `${data.varied} = ${(v * 180 / Math.PI).toFixed(1)}\u00b0` : `${data.varied} = ${fmt(v)}`;
}
let row = -1;
function show(k) {
  row = k;
  const f = data.frames[k];
  targets.forEach(([el, attr], i) => {
    if (attr === "translate" || attr === "rotate") el.setAttribute("transform", `${attr}(${f[i]})`);
    else el.setAttribute(attr, f[i]);
  });
  const r = data.rows[k];
  scrub.value = String(k);
  position.textContent = `position ${k + 1} of ${n}`;
  varied.textContent = variedText(r.values[0]);
  for (const [td, c] of cells) td.textContent = fmt(r.values[c]);
  note.hidden = r.note === null;
  note.textContent = r.note ?? "";
  svg.classList.toggle("noted", r.note !== null);
}
if (n === 0) { varied.textContent = "no positions"; play.disabled = scrub.disabled = true; return; }
const period = (data.seconds * 1000) / n;
let playing = false, start = 0, startRow = 0;
function setPlaying(p) {
  playing = p && n > 1;
  play.textContent = playing ? "Pause" : "Play";
  start = performance.now();
  startRow = row;
}
function tick(now) {
  if (playing) {
    const k = (startRow + Math.floor(Math.max(0, now - start) / period)) % n;
    if (k !== row) show(k);
  }
  requestAnimationFrame(tick);
}
play.addEventListener("click", () => setPlaying(!playing));
scrub.addEventListener("input", () => { setPlaying(false); show(Number(scrub.value)); });
document.addEventListener("keydown", (e) => {
  if (e.key === " " && e.target === document.body) { e.preventDefault(); setPlaying(!playing); }
});
show(0);
setPlaying(true);
requestAnimationFrame(tick);
})();"#;

/// The mechanism moving through its cycle as a self-contained HTML page:
/// the drawing (inline SVG), play/pause, a slider to scrub the position,
/// and the position's varied value, note and reactions as text. The
/// table's values and the drawing's positions are embedded as JSON.
/// `degrees`: the varied column is an angle in radians, shown in degrees.
pub fn animation_html(table: &CycleTable, title: &str, degrees: bool) -> String {
    let fig = figure(table);
    let json = script_json(&data(table, title, degrees, &fig.moving));
    let title = escape(title);
    let legend: String = table
        .drawing
        .bodies
        .iter()
        .enumerate()
        .map(|(b, body)| {
            format!(
                "<span><i class=\"swatch\" style=\"background:{}\"></i>{}</span>",
                hex(PALETTE[b % PALETTE.len()]),
                escape(&body.name)
            )
        })
        .collect();
    let last = table.rows.len().saturating_sub(1);
    format!(
        "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n\
         <meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n\
         <title>{title}</title>\n<style>\n{PAGE_STYLE}</style>\n</head>\n<body>\n<h1>{title}</h1>\n\
         <div class=\"layout\">\n<div class=\"stage\">\n\
         <svg id=\"mechanism\" viewBox=\"0 0 {w} {h}\" role=\"img\" aria-label=\"the mechanism\">{elements}</svg>\n\
         <div class=\"controls\"><button id=\"play\" type=\"button\">Pause</button>\
         <input id=\"scrub\" type=\"range\" min=\"0\" max=\"{last}\" step=\"1\" value=\"0\" aria-label=\"position\">\
         <span id=\"position\"></span>\
         <label><input id=\"forces\" type=\"checkbox\" checked> reactions</label></div>\n</div>\n\
         <aside>\n<div id=\"varied\"></div>\n<div id=\"note\" hidden></div>\n\
         <table id=\"reactions\"><tbody></tbody></table>\n\
         <p class=\"hint\">Each joint's reaction is the force on its second body from its first, \
         in ground components; a slider's across its guide. The arrows draw them to one scale.</p>\n\
         <p class=\"legend\">{legend}</p>\n</aside>\n</div>\n\
         <script type=\"application/json\" id=\"cycle-data\">{json}</script>\n\
         <script>\n{PLAYER}\n</script>\n</body>\n</html>\n",
        w = num(fig.view.width),
        h = num(fig.view.height),
        elements = fig.elements,
    )
}

/// The mechanism moving through its cycle as an animated SVG: every
/// moving attribute runs through its rows' values with SMIL (`<animate>`,
/// `<animateTransform>`) in a loop. No controls and no text but the title.
pub fn animation_svg(table: &CycleTable, title: &str) -> String {
    let fig = figure(table);
    let seconds = loop_seconds(table.rows.len());
    let mut animations = String::new();
    for ((id, attr), values) in fig.moving.targets.iter().zip(&fig.moving.values) {
        let values = values.join(";");
        let _ = if matches!(*attr, "translate" | "rotate") {
            writeln!(
                animations,
                "<animateTransform xlink:href=\"#{id}\" attributeName=\"transform\" type=\"{attr}\" \
                 values=\"{values}\" dur=\"{seconds}s\" repeatCount=\"indefinite\"/>"
            )
        } else {
            writeln!(
                animations,
                "<animate xlink:href=\"#{id}\" attributeName=\"{attr}\" \
                 values=\"{values}\" dur=\"{seconds}s\" repeatCount=\"indefinite\"/>"
            )
        };
    }
    let (w, h) = (num(fig.view.width), num(fig.view.height));
    let title = escape(title);
    format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" xmlns:xlink=\"http://www.w3.org/1999/xlink\" \
         viewBox=\"0 -60 {w} {h_all}\" width=\"{w}\" height=\"{h_all}\">\n<title>{title}</title>\n\
         <rect x=\"0\" y=\"-60\" width=\"{w}\" height=\"{h_all}\" fill=\"#fff\"/>\n\
         <text x=\"20\" y=\"-20\" style=\"font:bold 28px sans-serif;fill:#111\">{title}</text>\n\
         <svg x=\"0\" y=\"0\" width=\"{w}\" height=\"{h}\" viewBox=\"0 0 {w} {h}\">{elements}</svg>\n\
         {animations}</svg>\n",
        h_all = num(fig.view.height + 60.0),
        elements = fig.elements,
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::drawing::fixture::{slider_crank, slider_crank_at, with_dead_point};

    /// The JSON a page embeds, parsed.
    fn embedded(html: &str) -> Value {
        let open = "<script type=\"application/json\" id=\"cycle-data\">";
        let at = html.find(open).unwrap() + open.len();
        let len = html[at..].find("</script>").unwrap();
        serde_json::from_str(&html[at..at + len]).unwrap()
    }

    /// Writes the slider-crank's page, animated SVG and diagrams to
    /// target/ when QDOT_WRITE_DEMO is set, for scripts/animation_check.mjs
    /// (and a look); checks the page's data either way.
    #[test]
    fn writes_the_demo() {
        let table = slider_crank_at(73);
        let html = animation_html(&table, "Slider-crank (issue 36 demo)", true);
        assert_eq!(embedded(&html)["rows"].as_array().unwrap().len(), 73);
        if std::env::var_os("QDOT_WRITE_DEMO").is_some() {
            let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("target");
            std::fs::create_dir_all(&dir).unwrap();
            std::fs::write(dir.join("animation_demo.html"), &html).unwrap();
            let svg = animation_svg(&table, "Slider-crank (issue 36 demo)");
            std::fs::write(dir.join("animation_demo.svg"), svg).unwrap();
            let plot = crate::drawing::reaction_diagrams(&table, "Slider-crank: reactions", true);
            std::fs::write(dir.join("reactions_demo.svg"), plot.unwrap()).unwrap();
        }
    }

    #[test]
    fn the_page_fetches_nothing_and_its_data_round_trips() {
        let table = with_dead_point(4);
        let html = animation_html(&table, "slider-crank", true);
        for off in ["http", "//", "src=", "href", "@import", "@font-face"] {
            assert!(!html.contains(off), "the page has {off}");
        }
        assert_eq!(
            html.matches("url(").count(),
            html.matches("url(#hatch)").count() + html.matches("url(#arrow)").count()
        );
        let data = embedded(&html);
        let rows = data["rows"].as_array().unwrap();
        assert_eq!(rows.len(), table.rows.len());
        for (r, row) in rows.iter().zip(&table.rows) {
            // every value as its shortest exact decimal (JSON.parse reads
            // it back exactly; serde_json's own parser may miss by an ulp)
            let text = json!({ "values": row.values, "note": row.note }).to_string();
            assert!(html.contains(&text), "{text}");
            assert_eq!(r["values"].as_array().unwrap().len(), 33);
            assert_eq!(r["note"].as_str(), row.note.as_deref());
        }
        assert!(rows[4]["values"][25].is_null());
        assert_eq!(
            rows[4]["note"],
            "dead point: the constraints' Jacobian is singular"
        );
        assert_eq!(data["columns"][32], "M");
        assert_eq!(data["labels"][3], "φ");
        assert_eq!(data["joints"][1]["columns"], json!([27, 28]));
        assert_eq!(data["joints"][1]["on"], "rod");
        assert_eq!(data["drives"][0]["column"], 32);
        assert_eq!(data["degrees"], true);
    }

    #[test]
    fn the_frames_are_the_rows_points_on_the_view() {
        let table = slider_crank();
        let fig = figure(&table);
        let html = animation_html(&table, "slider-crank", true);
        let data = embedded(&html);
        let targets: Vec<(String, String)> =
            serde_json::from_value(data["targets"].clone()).unwrap();
        let frames: Vec<Vec<String>> = serde_json::from_value(data["frames"].clone()).unwrap();
        assert_eq!(frames.len(), 13);
        let find = |id: &str, attr: &str| {
            targets
                .iter()
                .position(|t| t.0 == id && t.1 == attr)
                .unwrap_or_else(|| panic!("{id} {attr} not in {targets:?}"))
        };
        // pin A (joint 1) at φ = 90°: the crank's end (0, 1)
        let (x, y) = fig.view.map([0.0, 1.0]);
        assert_eq!(frames[3][find("j1p", "cx")], num(x));
        assert_eq!(frames[3][find("j1p", "cy")], num(y));
        // the rod (body 1) is the bar from A to B; the crank from O to A
        let b = table.rows[3].points[5];
        let (bx, by) = fig.view.map(b);
        let bar = &frames[3][find("b1", "points")];
        assert!(bar.contains(&format!("{},{}", num(x), num(y))), "{bar}");
        assert!(bar.contains(&format!("{},{}", num(bx), num(by))), "{bar}");
        assert_eq!(bar.split(' ').count(), 2);
        // the block (a particle) translated to B, turned with the guide: 0°
        assert_eq!(
            frames[3][find("b2k", "translate")],
            format!("{},{}", num(bx), num(by))
        );
        assert_eq!(frames[3][find("b2kr", "rotate")], "0.0");
        // O's support and G's guide stay put; the first frame is drawn
        let o = find("j0s", "translate");
        assert!(frames.iter().all(|f| f[o] == frames[0][o]));
        assert!(html.contains(&format!("cx=\"{}\"", frames[0][find("j1p", "cx")])));
        // every point inside the view
        for f in &frames {
            let (x, y): (f64, f64) = (
                f[find("j2p", "cx")].parse().unwrap(),
                f[find("j2p", "cy")].parse().unwrap(),
            );
            assert!((0.0..=fig.view.width).contains(&x) && (0.0..=fig.view.height).contains(&y));
        }
        assert_eq!(fig.view.width, VIEW);
    }

    #[test]
    fn a_note_cannot_close_the_script() {
        let mut table = slider_crank();
        table.rows[2].note = Some("</script><!-- & <b>".into());
        let html = animation_html(&table, "a <title> & more", false);
        assert_eq!(html.matches("</script>").count(), 2);
        assert!(!html.contains("<!--"));
        assert!(html.contains("<title>a &lt;title&gt; &amp; more</title>"));
        let data = embedded(&html);
        assert_eq!(data["rows"][2]["note"], "</script><!-- & <b>");
        assert_eq!(data["title"], "a <title> & more");
    }

    #[test]
    fn a_row_without_finite_points_is_drawn_as_the_row_before() {
        let mut table = slider_crank();
        table.rows[5].points[2] = [f64::NAN, 0.0];
        table.rows[5].note = Some("no position".into());
        assert_eq!(drawable_rows(&table).unwrap()[4..7], [4, 4, 6]);
        let fig = figure(&table);
        let pin = fig
            .moving
            .targets
            .iter()
            .position(|t| t.0 == "j1p")
            .unwrap();
        assert_eq!(fig.moving.values[pin][5], fig.moving.values[pin][4]);
        assert_ne!(fig.moving.values[pin][6], fig.moving.values[pin][4]);
        table.rows[0].points.clear();
        assert_eq!(drawable_rows(&table).unwrap()[0..2], [1, 1]);
    }

    #[test]
    fn the_svg_animates_every_moving_attribute_through_every_row() {
        let table = slider_crank();
        let fig = figure(&table);
        let svg = animation_svg(&table, "slider-crank");
        assert!(svg.starts_with("<svg xmlns=\"http://www.w3.org/2000/svg\""));
        let animations: Vec<&str> = svg.split("<animate").skip(1).collect();
        assert_eq!(animations.len(), fig.moving.targets.len());
        let transforms = fig
            .moving
            .targets
            .iter()
            .filter(|t| matches!(t.1, "translate" | "rotate"))
            .count();
        assert_eq!(svg.matches("<animateTransform").count(), transforms);
        for (a, values) in animations.iter().zip(&fig.moving.values) {
            let v = &a[a.find("values=\"").unwrap() + 8..];
            let v = &v[..v.find('"').unwrap()];
            assert_eq!(v.split(';').collect::<Vec<_>>(), *values);
            assert!(a.contains("dur=\"2s\" repeatCount=\"indefinite\""));
        }
        assert!(svg.contains("xlink:href=\"#j1p\" attributeName=\"cx\""));
        assert_eq!(svg.matches("<svg").count(), 2);
    }

    #[test]
    fn the_reactions_are_arrows_to_one_scale_hidden_where_unknown() {
        let table = with_dead_point(4);
        let fig = figure(&table);
        let find = |id: &str, attr: &str| {
            let i = fig
                .moving
                .targets
                .iter()
                .position(|t| t.0 == id && t.1 == attr)
                .unwrap();
            &fig.moving.values[i]
        };
        // the largest force over the cycle, at φ = 0: the spring's
        // k (xb − l0) = 10 (4 − 3) along x, drawn a fifth of the view long
        let largest = table
            .rows
            .iter()
            .flat_map(|r| [(25, 26), (27, 28), (29, 30)].map(|(x, y)| (r.values[x], r.values[y])))
            .filter_map(|(x, y)| Some(x?.hypot(y?)))
            .fold(0.0, f64::max);
        assert_eq!(largest, 10.0);
        let scale = 0.2 * VIEW / largest;
        // pin A (joint 1) at φ = 90°: from A, along (A_x, −A_y) on the view
        let (ax, ay) = fig.view.map([0.0, 1.0]);
        let (fx, fy) = (
            table.rows[3].values[27].unwrap(),
            table.rows[3].values[28].unwrap(),
        );
        assert_eq!(
            find("j1f", "points")[3],
            format!(
                "{},{} {},{}",
                num(ax),
                num(ay),
                num(ax + fx * scale),
                num(ay - fy * scale)
            )
        );
        assert_eq!(find("j1f", "opacity")[3], "1");
        // the dead point: every arrow hidden; the slider's across its guide
        for j in 0..4 {
            assert_eq!(find(&format!("j{j}f"), "opacity")[4], "0");
        }
        let gn = table.rows[3].values[31].unwrap();
        let (bx, by) = fig.view.map(table.rows[3].points[8]);
        assert_eq!(
            find("j3f", "points")[3],
            format!(
                "{},{} {},{}",
                num(bx),
                num(by),
                num(bx),
                num(by - gn * scale)
            )
        );
    }

    #[test]
    fn a_body_is_drawn_around_its_points() {
        let at = [[0.0, 0.0], [2.0, 0.0], [1.0, 0.3], [1.0, 2.0], [1.0, 0.0]];
        // a triangle with its centre inside and a point on an edge
        assert_eq!(hull(&[2, 0, 1, 3, 4], &at), [0, 1, 3]);
        // a bar: its two ends
        assert_eq!(hull(&[4, 0, 1], &at), [0, 1]);
        // one point, twice
        assert_eq!(hull(&[0, 0], &at), [0]);
        assert_eq!(
            unwrapped(vec![170.0, -170.0, -10.0, 175.0]),
            [170.0, 190.0, 350.0, 175.0]
        );
    }
}
