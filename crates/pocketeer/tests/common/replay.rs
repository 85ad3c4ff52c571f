//! A test-only replay of G-code: reads the moves back from the program text (not from our
//! tool path values) and measures gouge and leftover against the pocket by exact distances
//! and a fine grid.

use pocketeer::geom::PreparedPocket;
use pocketeer::geom::{Arc, Line, Point, Segment, SegmentIndex, Tolerance};

/// One move read back, seen from above, with its Z at both ends.
#[derive(Debug, Clone)]
pub struct Read {
    pub segment: Segment,
    pub z0: f64,
    pub z1: f64,
    pub rapid: bool,
    pub line: usize,
}

/// Reads G0/G1/G2/G3 with X Y Z I J F words (incremental I/J, absolute coordinates,
/// millimetres or inches), comments in parentheses or after `;`.
pub fn read(program: &str) -> Result<Vec<Read>, String> {
    let mut pos = [0.0f64, 0.0, 0.0];
    let mut known_z = false;
    let mut motion = -1i32;
    let mut scale = 1.0;
    let mut out = Vec::new();
    for (n, raw) in program.lines().enumerate() {
        let mut text = String::new();
        let mut depth = 0;
        for c in raw.chars() {
            match c {
                '(' => depth += 1,
                ')' => depth -= 1,
                ';' if depth == 0 => break,
                c if depth == 0 => text.push(c.to_ascii_uppercase()),
                _ => {}
            }
        }
        let mut words: Vec<(char, f64)> = Vec::new();
        let mut chars = text.chars().filter(|c| !c.is_whitespace()).peekable();
        while let Some(letter) = chars.next() {
            let mut num = String::new();
            while let Some(&c) = chars.peek() {
                if c.is_ascii_digit() || c == '.' || c == '-' || c == '+' {
                    num.push(c);
                    chars.next();
                } else {
                    break;
                }
            }
            let v: f64 = num
                .parse()
                .map_err(|_| format!("line {}: bad word {letter}{num}", n + 1))?;
            words.push((letter, v));
        }
        let (mut target, mut ij, mut moved) = (pos, [0.0, 0.0], false);
        for &(l, v) in &words {
            match l {
                'G' if [0.0, 1.0, 2.0, 3.0].contains(&v) => motion = v as i32,
                'G' if v == 20.0 => scale = 25.4,
                'G' if v == 21.0 => scale = 1.0,
                'X' => (target[0], moved) = (v * scale, true),
                'Y' => (target[1], moved) = (v * scale, true),
                'Z' => (target[2], moved, known_z) = (v * scale, true, true),
                'I' => ij[0] = v * scale,
                'J' => ij[1] = v * scale,
                _ => {}
            }
        }
        if !moved {
            continue;
        }
        if !known_z {
            return Err(format!("line {}: XY move before any Z", n + 1));
        }
        let (a, b) = (Point::new(pos[0], pos[1]), Point::new(target[0], target[1]));
        let segment = match motion {
            0 | 1 => Segment::Line(Line::new(a, b)),
            2 | 3 => {
                let c = Point::new(pos[0] + ij[0], pos[1] + ij[1]);
                let (r0, r1) = (c.distance(a), c.distance(b));
                if (r0 - r1).abs() > 0.001 {
                    return Err(format!(
                        "line {}: arc end off its circle by {:.6}",
                        n + 1,
                        (r0 - r1).abs()
                    ));
                }
                let mut sweep = (b - c).angle() - (a - c).angle();
                if motion == 3 && sweep <= 0.0 {
                    sweep += std::f64::consts::TAU;
                }
                if motion == 2 && sweep >= 0.0 {
                    sweep -= std::f64::consts::TAU;
                }
                Segment::Arc(Arc::new(c, r0, (a - c).angle(), sweep))
            }
            _ => return Err(format!("line {}: move without a motion mode", n + 1)),
        };
        out.push(Read {
            segment,
            z0: pos[2],
            z1: target[2],
            rapid: motion == 0,
            line: n + 1,
        });
        pos = target;
    }
    Ok(out)
}

/// True when every sample of the tool disc of radius `r` at `p` (its centre and a ring just
/// inside its edge) lies within `r` of one of `cuts` where that cut was at `z` or below: the
/// stock there was cut down past `z`. Brute force over every cut.
fn disc_cut_before(cuts: &[&Read], p: Point, z: f64, r: f64) -> bool {
    let ring = (0..12).map(|k| {
        let a = std::f64::consts::TAU * k as f64 / 12.0;
        p + pocketeer::geom::Vector::from_angle(a) * (0.95 * r)
    });
    std::iter::once(p).chain(ring).all(|q| {
        cuts.iter().any(|c| {
            let t = pocketeer::geom::closest_param(&c.segment, q);
            c.segment.point_at(t).distance(q) <= r + 1e-3 && c.z0 + (c.z1 - c.z0) * t <= z + 1e-4
        })
    })
}

/// What a replay measured.
#[derive(Debug)]
pub struct Measured {
    /// Largest depth by which the tool disc goes outside the region below Z=0, mm.
    pub gouge: f64,
    pub gouge_line: usize,
    /// Reachable grid points farther than the radius (plus `slack`) from every cut at the
    /// final depth.
    pub leftover_points: Vec<Point>,
    /// Reachable grid points tested.
    pub tested: usize,
    pub rapids_below_top: usize,
    pub deepest: f64,
}

/// One pocket as the replay sees it: its region, its walls and islands, and the loops of the
/// region eroded by the tool radius (the boundary of where the tool centre may go).
pub struct Target<'a> {
    pub region: &'a PreparedPocket,
    pub walls: &'a [Segment],
    pub centres: &'a [Segment],
}

/// Replays `moves` for a tool of radius `r` over the pockets `targets`. Gouge: how far the tool
/// disc of a feed move below Z=0 reaches outside the pocket it is in (the pocket that makes
/// this smallest). Leftover is tested on a grid of step `h`: points of a pocket at least `r`
/// from every wall, or within `r - slack` of its `centres`, are reachable, and each must lie
/// within `r + slack` of a cut at `depth`.
pub fn measure(moves: &[Read], targets: &[Target], r: f64, depth: f64, h: f64, slack: f64) -> Measured {
    let tol = Tolerance::default();
    let mut m = Measured {
        gouge: 0.0,
        gouge_line: 0,
        leftover_points: Vec::new(),
        tested: 0,
        rapids_below_top: 0,
        deepest: 0.0,
    };
    let wall_indexes: Vec<SegmentIndex> = targets.iter().map(|t| SegmentIndex::new(t.walls)).collect();
    let mut floor: Vec<Segment> = Vec::new();
    let mut below_top: Vec<&Read> = Vec::new();
    for mv in moves {
        m.deepest = m.deepest.min(mv.z1);
        if mv.rapid {
            // Straight up out of the cut, or straight down onto stock cut deeper than where it
            // stops, a rapid moves through air; any other below Z=0 moves through the stock.
            let vertical = mv.segment.length() <= 1e-6;
            let p = mv.segment.start();
            let onto_cut = vertical && mv.z1 < mv.z0 && disc_cut_before(&below_top, p, mv.z1, r);
            if mv.z0.min(mv.z1) < -1e-9 && !(vertical && mv.z1 >= mv.z0) && !onto_cut {
                m.rapids_below_top += 1;
            }
            continue;
        }
        if mv.z0.min(mv.z1) < 0.0 {
            below_top.push(mv);
        }
        if mv.z0.min(mv.z1) < -1e-9 {
            let mut gouge = f64::INFINITY;
            for (t, index) in targets.iter().zip(&wall_indexes) {
                // Exact nearest distance from the centre path to the walls, and inside or not.
                let b = mv.segment.bbox();
                let mid = mv.segment.point_at(0.5);
                let near = index.distance(mid);
                // Walls farther than the tool from every point of the move cannot decide.
                let reach = near + 0.5 * b.width().hypot(b.height()) + r;
                let worst = t
                    .walls
                    .iter()
                    .filter(|w| w.bbox().inflated(reach).contains(mid))
                    .map(|w| pocketeer::geom::segment_distance(w, &mv.segment, tol.eps).0)
                    .fold(f64::INFINITY, f64::min);
                let inside = t.region.contains(mid) || near < 1e-6;
                gouge = gouge.min(if inside { r - worst } else { r + worst });
            }
            if gouge > m.gouge {
                m.gouge = gouge;
                m.gouge_line = mv.line;
            }
        }
        if (mv.z0 - depth).abs() < 1e-3 && (mv.z1 - depth).abs() < 1e-3 && mv.segment.length() > 0.0 {
            floor.push(mv.segment);
        }
    }
    let cut_index = SegmentIndex::new(&floor);
    for t in targets {
        let centre_index = SegmentIndex::new(t.centres);
        let bbox = t
            .walls
            .iter()
            .fold(pocketeer::geom::Aabb::EMPTY, |b, s| b.union(&s.bbox()));
        let (nx, ny) = (
            (bbox.width() / h).ceil() as usize,
            (bbox.height() / h).ceil() as usize,
        );
        for i in 0..=nx {
            for j in 0..=ny {
                let p = Point::new(bbox.min.x + i as f64 * h, bbox.min.y + j as f64 * h);
                if !t.region.contains(p)
                    || !(t.region.distance(p) >= r || centre_index.any_within(p, r - slack))
                {
                    continue;
                }
                m.tested += 1;
                if cut_index.distance(p) > r + slack {
                    m.leftover_points.push(p);
                }
            }
        }
    }
    m
}

/// Wall-following length of the feed moves at `depth` (both ends within a micrometre of it) by
/// the side the nearest wall is on, for a tool of radius `r`: (right, left). A move follows a
/// wall where its centre is within 0.005 mm of `r` from the nearest of `walls`, found by
/// trying every wall segment; moves are sampled every 0.05 mm.
pub fn wall_sides(moves: &[Read], walls: &[Segment], r: f64, depth: f64) -> (f64, f64) {
    let (mut right, mut left) = (0.0, 0.0);
    for mv in moves {
        if mv.rapid || (mv.z0 - depth).abs() > 1e-3 || (mv.z1 - depth).abs() > 1e-3 {
            continue;
        }
        let len = mv.segment.length();
        let n = (len / 0.05).ceil().max(1.0) as usize;
        for k in 0..n {
            let t = (k as f64 + 0.5) / n as f64;
            let c = mv.segment.point_at(t);
            let (d, w) = walls
                .iter()
                .map(|s| {
                    let w = pocketeer::geom::closest_point(s, c);
                    (w.distance(c), w)
                })
                .fold((f64::INFINITY, c), |a, b| if b.0 < a.0 { b } else { a });
            if (d - r).abs() > 0.005 {
                continue;
            }
            // Ahead along the move and towards the wall: the wall is on the right when turning
            // from the first to the second is clockwise.
            let ahead = mv.segment.point_at((t + 1e-3).min(1.0)) - mv.segment.point_at((t - 1e-3).max(0.0));
            if ahead.cross(w - c) < 0.0 {
                right += len / n as f64;
            } else {
                left += len / n as f64;
            }
        }
    }
    (right, left)
}
