//! `georod modes SCENE.toml`: the natural frequencies of a scene's initial state (its static
//! equilibrium under the constant loads and prescribed displacements; harmonic and input loads
//! off), printed, and the mode shapes written as CSV and drawn as SVG.
use crate::args::Options;
use georod::model::modal_subspace::lowest_modes;
use georod::model::Assembly;
use georod::scene::Scene;
use georod::simulation::readouts::hertz;
use georod::simulation::setup::MemberRole;
use georod::simulation::Simulation;
use nalgebra::Vector2;
use std::fmt::Write as _;
use std::sync::Arc;

/// What `georod modes FILE.toml` prints and writes.
pub struct ModalReport {
    /// The frequencies, printed.
    pub text: String,
    /// `node,s,x,y` (a frame: `member,node,s,x,y`, member by member), then `u1_k,u2_k,w_k` per
    /// mode (each shape scaled so that its largest translation is +1).
    pub csv: String,
    /// One panel per mode: the rod in its initial state and displaced along the mode.
    pub svg: String,
}

/// The natural frequencies and mode shapes of the scene in `file` (with `o`'s overrides).
pub fn modes_of_scene(file: &str, o: &Options) -> Result<ModalReport, String> {
    let scene = Arc::new(Scene::load(file).map_err(|e| e.to_string())?);
    let values = scene
        .values_with(o.overrides.iter().map(|(k, v)| (k.as_str(), *v)))
        .map_err(|e| e.to_string())?;
    let sim = Simulation::new(scene.clone(), values).map_err(|e| format!("{file}: {e}"))?;
    let structure = sim.structure();
    let u = &sim.state().u;
    let free = structure.dofs() - structure.constrained().len();
    let count = o.count.min(free);
    let modes = lowest_modes(structure, u, count).map_err(|e| format!("{file}: {e}"))?;
    let mut report = format!(
        "{}: {} elements, natural frequencies of the initial state (undamped; constant loads on, \
         harmonic and input loads off)\n{:>5} {:>16} {:>16}\n",
        scene.name,
        sim.values().elements(),
        "mode",
        "frequency/Hz",
        "omega/(rad/s)"
    );
    let drawing = Drawing::of(&sim);
    let frame = scene.frame.is_some();
    let mut csv = String::from(if frame {
        "member,node,s,x,y"
    } else {
        "node,s,x,y"
    });
    for k in 1..=count {
        let _ = write!(csv, ",u1_{k},u2_{k},w_{k}");
    }
    csv.push('\n');
    let shapes: Vec<Vec<f64>> = modes.iter().map(|(_, shape)| scaled(shape)).collect();
    let frequencies: Vec<f64> = modes.iter().map(|(lambda, _)| hertz(*lambda)).collect();
    let svg = plot(&scene.name, &drawing, &shapes, &frequencies);
    for (k, (lambda, _)) in modes.iter().enumerate() {
        let f = hertz(*lambda);
        let note = if *lambda < 0.0 {
            "  (unstable: -sqrt(-omega^2))"
        } else {
            ""
        };
        let _ = writeln!(
            report,
            "{:>5} {:>16.8e} {:>16.8e}{note}",
            k + 1,
            f,
            f * std::f64::consts::TAU
        );
    }
    for p in &drawing.points {
        if frame {
            let _ = write!(csv, "{},", p.member);
        }
        let _ = write!(csv, "{},{:e},{:e},{:e}", p.node, p.s, p.x[0], p.x[1]);
        for shape in &shapes {
            let d = p.dof;
            let _ = write!(csv, ",{:e},{:e},{:e}", shape[d], shape[d + 1], shape[d + 2]);
        }
        csv.push('\n');
    }
    Ok(ModalReport {
        text: report,
        csv,
        svg,
    })
}

/// A node drawn: its member's name (a frame), its index in the member, its arc length, its
/// position in the initial state and its first dof.
struct Point {
    member: String,
    node: usize,
    s: f64,
    x: [f64; 2],
    dof: usize,
}

/// The nodes of every member in order, and each member's polyline (indices into `points`).
struct Drawing {
    points: Vec<Point>,
    lines: Vec<Vec<usize>>,
}

impl Drawing {
    fn of(sim: &Simulation) -> Drawing {
        let structure = sim.structure();
        let u = &sim.state().u;
        let mut d = Drawing {
            points: Vec::new(),
            lines: Vec::new(),
        };
        let names: Vec<String> = match &sim.scene().frame {
            None => vec![String::new()],
            Some(f) => f.members.iter().map(|m| m.name.clone()).collect(),
        };
        for (role, name) in sim.setup().members.iter().zip(names) {
            let mut line = Vec::new();
            match *role {
                MemberRole::Rod(r) => {
                    let m = &structure.members[r];
                    for i in 0..m.rod.nodes() {
                        line.push(d.points.len());
                        d.points.push(Point {
                            member: name.clone(),
                            node: i,
                            s: m.rod.node_s[i],
                            x: m.rod.node_position(&u[m.range()], i).into(),
                            dof: m.offset + 3 * i,
                        });
                    }
                }
                MemberRole::Bar(b) => {
                    let bar = &structure.axial[b];
                    for (i, node) in bar.nodes.iter().enumerate() {
                        line.push(d.points.len());
                        let x = bar.reference[i] + Vector2::new(u[3 * node], u[3 * node + 1]);
                        d.points.push(Point {
                            member: name.clone(),
                            node: i,
                            s: i as f64 * bar.rest,
                            x: x.into(),
                            dof: 3 * node,
                        });
                    }
                }
            }
            d.lines.push(line);
        }
        d
    }
}

/// Width of the SVG drawing and the margin around each panel, in pixels.
const WIDTH: f64 = 640.0;
const MARGIN: f64 = 20.0;

/// The mode shapes as SVG: per mode a panel with the rod in its initial state (grey) and
/// displaced along the mode (blue) by a tenth of its extent, in true proportions.
fn plot(name: &str, drawing: &Drawing, shapes: &[Vec<f64>], frequencies: &[f64]) -> String {
    let positions: Vec<[f64; 2]> = drawing.points.iter().map(|p| p.x).collect();
    let (lo, hi) = positions.iter().fold(
        ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]),
        |(lo, hi), p| {
            (
                [lo[0].min(p[0]), lo[1].min(p[1])],
                [hi[0].max(p[0]), hi[1].max(p[1])],
            )
        },
    );
    let extent = (hi[0] - lo[0]).max(hi[1] - lo[1]).max(f64::MIN_POSITIVE);
    let amplitude = 0.1 * extent;
    let scale = (WIDTH - 2.0 * MARGIN) / (hi[0] - lo[0] + 2.0 * amplitude).max(extent);
    let panel = (hi[1] - lo[1] + 2.0 * amplitude) * scale + 2.0 * MARGIN + 14.0;
    let mut svg = format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{WIDTH}\" height=\"{:.0}\" \
         font-family=\"sans-serif\" font-size=\"12\">\n",
        panel * shapes.len() as f64
    );
    let line = |points: &mut dyn Iterator<Item = [f64; 2]>, top: f64, colour: &str| {
        let coords: Vec<String> = points
            .map(|[x, y]| {
                let px = MARGIN + (x - lo[0] + amplitude) * scale;
                let py = top + 14.0 + MARGIN + (hi[1] + amplitude - y) * scale;
                format!("{px:.2},{py:.2}")
            })
            .collect();
        format!(
            "<polyline fill=\"none\" stroke=\"{colour}\" stroke-width=\"2\" points=\"{}\"/>\n",
            coords.join(" ")
        )
    };
    for (k, (shape, f)) in shapes.iter().zip(frequencies).enumerate() {
        let top = k as f64 * panel;
        let _ = writeln!(
            svg,
            "<text x=\"{MARGIN}\" y=\"{:.1}\">{name}: mode {} at {f:.6e} Hz</text>",
            top + MARGIN,
            k + 1
        );
        for members in &drawing.lines {
            let points = members.iter().map(|&i| &drawing.points[i]);
            svg += &line(&mut points.clone().map(|p| p.x), top, "#999999");
            svg += &line(
                &mut points.map(|p| {
                    [
                        p.x[0] + amplitude * shape[p.dof],
                        p.x[1] + amplitude * shape[p.dof + 1],
                    ]
                }),
                top,
                "#1f77b4",
            );
        }
    }
    svg + "</svg>\n"
}

/// A mode shape scaled so that its largest translation is +1 (a pure rotation: its largest
/// rotation).
fn scaled(shape: &[f64]) -> Vec<f64> {
    let translations = shape
        .chunks(3)
        .flat_map(|node| [node[0], node[1]])
        .max_by(|a, b| a.abs().total_cmp(&b.abs()))
        .unwrap_or(0.0);
    let largest = if translations != 0.0 {
        translations
    } else {
        shape
            .iter()
            .copied()
            .max_by(|a, b| a.abs().total_cmp(&b.abs()))
            .unwrap_or(1.0)
    };
    shape.iter().map(|x| x / largest).collect()
}
