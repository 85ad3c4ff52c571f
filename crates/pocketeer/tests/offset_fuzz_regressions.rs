//! Inputs the `offset` fuzz target (fuzz/src/bin/offset.rs) found, built the same way: a
//! bulged polygon in hundredths of a millimetre (bulge in 128ths), round islands, a distance
//! in micrometres above 0.01 mm. Each runs from every start vertex and in both directions (the
//! polygon drawn the other way round), and every offset must pass
//! [`pocketeer::offset::verify_offset`]: closed loops, every point at distance d from the
//! walls and inside the pocket. The table holds the inputs with a one-line note on what each
//! exercises; the tests after it check more than the invariants.

use pocketeer::geom::Pocket;
use pocketeer::geom::{point_distance, Arc, Contour, Line, Point, Segment, Tolerance};

/// A fuzz input's vertex: x, y in hundredths of a millimetre, the bulge of the edge to the
/// next in 128ths (wider than the input's i8 so that a reversed -128 stays exact).
type Vertex = (i16, i16, i16);

/// How the fuzz target takes a polygon.
#[derive(Clone, Copy, Debug)]
enum Take {
    /// As drawn, turned counter-clockwise.
    Outline,
    /// Through the importer (which cuts away sliver loops), as the target takes it now.
    Imported,
}

/// One input: the polygon, round islands (x, y in hundredths, radius 0.1 + r/20 mm) and the
/// distance (0.01 + distance/1000 mm).
struct Case {
    note: &'static str,
    take: Take,
    vertices: &'static [(i16, i16, i8)],
    islands: &'static [(i16, i16, u8)],
    distance: u16,
}

const CASES: &[Case] = &[
    Case {
        note: "a joining chord between offset arcs is judged alone, not with them (d = 64.01)",
        take: Take::Outline,
        vertices: &[(3968, 3855, 15), (3855, 3855, 15), (3855, 100, 15), (31503, 31611, 123), (-17522, 3855, -15)],
        islands: &[],
        distance: 64000,
    },
    Case {
        note: "the same outline at d = 0.042",
        take: Take::Outline,
        vertices: &[(3968, 3855, 15), (3855, 3855, 15), (3855, 100, 15), (31503, 31611, 123), (-17522, 3855, -15)],
        islands: &[],
        distance: 32,
    },
    Case {
        note: "a tiny bulged triangle with islands at d = 0.01",
        take: Take::Outline,
        vertices: &[(13107, 13105, 51), (-77, -1, -128), (13107, 13107, -128)],
        islands: &[(13105, 13107, 51), (13107, 13107, 0)],
        distance: 0,
    },
    Case {
        note: "a tiny bulged quadrilateral, island at the origin, d = 0.01",
        take: Take::Outline,
        vertices: &[(13107, 13105, 1), (12979, 13107, 0), (13070, 13107, 51), (12583, 13122, 51)],
        islands: &[(0, 0, 0)],
        distance: 0,
    },
    Case {
        note: "a tiny bulged pentagon at d = 0.01",
        take: Take::Outline,
        vertices: &[(13107, 13105, 1), (12979, 13107, 0), (13070, 13107, 51), (12595, 13107, 51), (51, 0, 0)],
        islands: &[],
        distance: 0,
    },
    Case {
        note: "another tiny bulged quadrilateral, island at the origin, d = 0.01",
        take: Take::Outline,
        vertices: &[(13107, 13109, 1), (13235, 13107, 0), (13183, 13107, 51), (13619, 13107, 19)],
        islands: &[(0, 0, 0)],
        distance: 0,
    },
    Case {
        note: "a tiny arc hooking back by 179.97° between big arcs is a slit, not a needle",
        take: Take::Outline,
        vertices: &[(512, 0, 85), (21845, 21845, 85), (21852, 21845, 127), (15561, 25669, -97)],
        islands: &[],
        distance: 19775,
    },
    Case {
        note: "the same hook with a flatter last arc",
        take: Take::Outline,
        vertices: &[(512, 0, 85), (21845, 21845, 85), (21852, 21845, 85), (15561, 32767, -62)],
        islands: &[],
        distance: 19775,
    },
    Case {
        note: "a needle 0.02 mm wide at d = 0.01, its sides crossing node arcs almost tangentially",
        take: Take::Outline,
        vertices: &[(1, 4352, 0), (1, -12001, -24), (0, -20, 0), (-1, 4352, -5), (-1029, 24452, 1), (428, 11008, 1)],
        islands: &[(-1, 5118, 0), (2, 11027, 0), (-1712, -21416, 28)],
        distance: 0,
    },
    Case {
        note: "a needle 0.02 mm wide with two islands; circles of radii 9178 and 0.01 crossing shallowly",
        take: Take::Outline,
        vertices: &[(1, 4096, 0), (0, -8405, -9), (-1, 4096, -1), (752, 32767, 0)],
        islands: &[(-1029, -1954, 199), (15420, 1275, 0)],
        distance: 0,
    },
    Case {
        note: "a right turn of 97° into an arc curling by 160° gets its node arc",
        take: Take::Outline,
        vertices: &[(53, 4096, 0), (-9253, -9253, -37), (-23388, -9253, -37), (-9253, 6347, -108), (-6429, 5945, 68), (2, 19331, -42)],
        islands: &[],
        distance: 47408,
    },
    Case {
        note: "the same turn, the first vertex moved",
        take: Take::Outline,
        vertices: &[(-129, 2356, 13), (-9253, -9253, -37), (-23388, -9253, -37), (-9253, 6347, -108), (-6426, 5945, 68), (2, 19331, -42)],
        islands: &[],
        distance: 47408,
    },
    Case {
        note: "a bump of radius exactly d offsets onto its centre, not to a chord",
        take: Take::Outline,
        vertices: &[(-12851, 1261, -128), (-12851, 1263, 0), (-12851, 1519, -128), (-12851, -5313, 124), (2362, -6449, -51), (12160, -13130, -51), (-12928, -12817, -51), (-13113, -12851, -51), (-12851, -32563, -128), (-12851, -32563, -51), (-12851, -14545, -52), (-12851, -4224, -51), (-12851, 0, 0)],
        islands: &[],
        distance: 0,
    },
    Case {
        note: "three semicircles of radius d leave no sliver loop where offsets touch",
        take: Take::Outline,
        vertices: &[(-12850, 1261, -128), (-12852, 1261, -128), (-12852, 1263, -128), (-12862, -12851, 127)],
        islands: &[],
        distance: 0,
    },
    Case {
        note: "a line meeting a semicircle 0.02 mm across at 179.1° (d = 0.622), islands",
        take: Take::Outline,
        vertices: &[(-12851, -128, -128), (-12849, -128, 0), (-12851, -1, -51), (-12851, -12820, -33)],
        islands: &[(-12851, 256, 191), (16331, 31717, 248)],
        distance: 612,
    },
    Case {
        note: "semicircles 0.02 mm across among long edges, an island, d = 38.259",
        take: Take::Outline,
        vertices: &[(-12819, 17613, 0), (-2609, -32563, 0), (-20019, -32563, 0), (-12851, -12852, -55), (-12851, -12851, -52), (-12855, -12851, -85), (-12851, 1261, -128), (-12851, 1263, -128), (-13107, 16380, -32)],
        islands: &[(-15497, 28651, 244)],
        distance: 38249,
    },
    Case {
        note: "a line turning back into a semicircle 0.02 mm across, an island, d = 5.955",
        take: Take::Outline,
        vertices: &[(-12851, -128, -128), (-12849, -128, 0), (-12850, -33, -128), (4864, -12850, -33), (-9472, -9253, -37), (-9253, -32566, -37), (-13349, -27624, -101)],
        islands: &[(6347, -25726, 230)],
        distance: 5945,
    },
    Case {
        note: "a line turning back into a semicircle 0.02 mm across, islands, d = 32.188",
        take: Take::Outline,
        vertices: &[(-12850, -128, -128), (-12849, -128, 0), (-12850, -33, -128), (4864, -7617, -118)],
        islands: &[(20325, -12705, 205), (255, 0, 2)],
        distance: 32178,
    },
    Case {
        note: "a bulged pentagon with near reversals, d = 42.436",
        take: Take::Outline,
        vertices: &[(-14908, -14907, -59), (-14907, -14907, -59), (-14907, -23099, -91), (-23131, -23131, -91), (-6849, -14424, 53)],
        islands: &[],
        distance: 42426,
    },
    Case {
        note: "a bulged pentagon with near reversals, d = 56.087",
        take: Take::Outline,
        vertices: &[(-14908, -14907, -59), (-14907, -14907, -59), (16837, -23238, -91), (-23131, -23131, -91), (-91, 127, 0)],
        islands: &[],
        distance: 56077,
    },
    Case {
        note: "a 175.5° right turn into an arc curling the other way keeps its tip arc",
        take: Take::Outline,
        vertices: &[(-12851, 1261, -128), (19916, 1261, -37), (-9419, -9308, -37), (-23388, -26215, -103), (-26215, -26215, -128), (-12852, 1263, -128), (-12851, 1263, 5)],
        islands: &[(-26215, -26215, 153), (-12928, -12852, 239)],
        distance: 65408,
    },
    Case {
        note: "the same kind of turn, second input",
        take: Take::Outline,
        vertices: &[(-12851, 1261, -128), (19916, 1261, -37), (-9419, -9308, -37), (-23388, -26215, -103), (-26215, -26215, -128), (-12852, 1263, -128), (-12851, 1263, 5)],
        islands: &[],
        distance: 64260,
    },
    Case {
        note: "the same kind of turn, third input",
        take: Take::Outline,
        vertices: &[(-12851, 1261, -128), (19916, 1261, -37), (-9419, -9308, -37), (-23388, -26266, -103), (-26215, -26215, -128), (-12852, 1263, -128), (-12851, 1263, 5)],
        islands: &[],
        distance: 62211,
    },
    Case {
        note: "a left turn of 3e-5 rad out of a semicircle of radius d closes its loop where the walk returns",
        take: Take::Outline,
        vertices: &[(-25188, -25709, 1), (-25701, -25701, -128), (-25701, -25668, -128)],
        islands: &[],
        distance: 155,
    },
    Case {
        note: "an arc of radius d + 1.6e-5 crossing its neighbour 0.9 µm from their joint (lobe removed on import)",
        take: Take::Imported,
        vertices: &[(-1, 32634, -128), (24705, -32257, 0), (-32383, -32387, -121), (-32383, -32385, -7), (-32639, -32383, -127), (-1663, -1, 4), (0, 0, 0)],
        islands: &[],
        distance: 0,
    },
    Case {
        note: "a wiggle of arcs crossing again 0.9 µm from a joint, with islands, d = 1.237",
        take: Take::Imported,
        vertices: &[(21933, 21846, 86), (21781, 21845, 85), (20584, 21845, 85), (20565, 21846, 0), (20817, 20849, 81), (20817, 20958, -84), (20817, 20817, 81), (20817, 20737, 81), (128, 257, 0), (289, 279, 1), (376, 257, 1), (265, 257, 1), (257, 273, 1), (257, 257, 1), (257, 257, 1), (257, 257, 1), (257, 257, 1), (257, 1, -4), (-515, -1, -1), (-768, -627, -3), (-531, 16149, -32), (-20759, 13421, -3), (-1473, 0, -6), (-13516, -30719, 0), (32639, 32606, 127), (32640, 32636, 127), (32639, 32637, 127), (32639, 32638, -128), (32638, 32639, 127), (32637, 32639, 127), (32257, 32681, 127), (28211, 32767, 127), (28724, 31624, -47)],
        islands: &[(31448, 28287, 32), (32513, 30335, 146), (30335, 32597, 0), (5461, 22101, 85), (5461, 20565, 81), (16188, 26378, 252), (-20818, -11858, 209), (-11823, -11823, 63)],
        distance: 1227,
    },
    Case {
        note: "two arcs 0.008 and 0.006 mm in radius turning back by 173° at a joint, d = 0.5",
        take: Take::Imported,
        vertices: &[(66, 10241, 1), (257, 257, 0), (257, 257, 0), (257, 257, 0), (257, 256, 0), (257, 257, 0), (257, 256, 0), (257, 257, 0), (257, 257, 0), (257, 256, 0), (257, 256, 0), (257, 257, 0), (257, 256, 0), (257, 257, 0), (257, 256, 0), (257, 257, 0), (257, 257, 0), (257, 256, 0), (257, 256, 0), (257, 257, 0), (257, 257, 0), (257, 256, 0), (257, 256, 0), (257, 257, 0), (257, 256, 0), (257, 257, 0), (257, 256, 0), (257, 257, 0), (257, 256, 0), (257, 257, 0), (257, 256, 0), (257, 256, 0), (257, 257, 0), (257, 256, 0), (257, 256, 0), (257, 257, 0), (257, 257, 0), (257, 256, 0), (257, 256, 0), (257, 257, 0), (257, 256, 0), (257, 257, 0), (257, 256, 0), (257, 257, 0), (257, 256, 0), (257, 256, 0), (257, 256, 0), (257, 257, 0), (9826, 24756, 0), (17733, 18757, 122), (17733, 17765, 117), (17732, 17733, 47), (17733, 17733, 69), (17733, 17732, 65), (17987, 17474, -79), (-4113, -4113, -106), (-4113, -4113, -49), (-12337, -19249, 70), (26607, 26471, 103), (26471, 26471, 103), (26471, 26471, 103), (26471, 26471, 103), (26471, 26471, 103), (26471, 26471, 103)],
        islands: &[(-12337, -1570, 1), (256, 256, 1)],
        distance: 490,
    },
    Case {
        note: "a wedge 79 mm long closing to a round end of radius d, an island",
        take: Take::Imported,
        vertices: &[(-1, -1, -1), (-7936, 128, -1), (-1, 1, -128)],
        islands: &[(19455, 0, 0)],
        distance: 0,
    },
    Case {
        note: "a wedge closing to a round end of radius d, four vertices",
        take: Take::Imported,
        vertices: &[(-1, 1, -128), (-1, -1, -1), (-13312, -30336, 0), (-1214, 0, 0)],
        islands: &[],
        distance: 0,
    },
    Case {
        note: "a stitching walk that ends dead after closing a loop leaves no stale mark",
        take: Take::Imported,
        vertices: &[(31, 7167, 0), (-2, 0, 126), (0, 0, 0)],
        islands: &[],
        distance: 0,
    },
];

#[test]
fn every_input_from_every_start_in_both_directions() {
    for case in CASES {
        for (label, v) in variants(case.vertices) {
            let boundary = match case.take {
                Take::Outline => outline(&v),
                Take::Imported => match imported(&v[..v.len().min(64)]) {
                    Some(boundary) => boundary,
                    // Known: see `the_importers_verdict_does_not_depend_on_start_or_direction`.
                    None if case.note == REFUSED_FROM_SOME_STARTS => continue,
                    None => panic!("{} ({label}): the importer refuses the outline", case.note),
                },
            };
            let islands = round_islands(&boundary, &case.islands[..case.islands.len().min(4)]);
            let pocket = Pocket { boundary, islands };
            let d = distance(case.distance);
            if let Err(fault) = verified_loops(&pocket, d) {
                panic!("{} ({label}, {:?}, d = {d}): {fault}", case.note, case.take);
            }
        }
    }
}

/// `vertices` from every start vertex, as given and reversed, with a label for messages.
fn variants(vertices: &[(i16, i16, i8)]) -> Vec<(String, Vec<Vertex>)> {
    let given: Vec<Vertex> = vertices.iter().map(|&(x, y, b)| (x, y, b as i16)).collect();
    let n = given.len();
    // Reversed, vertex k+1 starts the edge that was k: it carries that edge's bulge, negated.
    let reversed: Vec<Vertex> = (0..n)
        .rev()
        .map(|k| {
            let (x, y, _) = given[(k + 1) % n];
            (x, y, -given[k].2)
        })
        .collect();
    let mut out = Vec::new();
    for (way, v) in [("as given", given), ("reversed", reversed)] {
        for start in 0..n {
            let mut turned = v.clone();
            turned.rotate_left(start);
            out.push((format!("{way}, from vertex {start}"), turned));
        }
    }
    out
}

/// The label of the variant as the fuzz target drew it.
const DRAWN: &str = "as given, from vertex 0";

fn distance(input: u16) -> f64 {
    0.01 + input as f64 / 1000.0
}

/// The offset of `pocket` by `d`, when it passes [`pocketeer::offset::verify_offset`].
fn verified_loops(pocket: &Pocket, d: f64) -> Result<Vec<Contour>, pocketeer::offset::OffsetFault> {
    let tol = Tolerance::for_extent(&pocket.boundary.bbox(), 0.001);
    let loops = pocketeer::offset::offset_pocket(pocket, d, &tol).expect("no input here is too complex");
    pocketeer::offset::verify_offset(pocket, &loops, d)?;
    Ok(loops)
}

/// [`verified_loops`] at the fuzz input's distance, failing the test on a fault.
fn check(pocket: &Pocket, distance_input: u16) -> Vec<Contour> {
    let d = distance(distance_input);
    verified_loops(pocket, d).unwrap_or_else(|f| panic!("d = {d}: {f}"))
}

/// The bulged polygon of the fuzz input, in its own direction (edges under 1 µm dropped).
fn polygon(vertices: &[Vertex]) -> Contour {
    let pts: Vec<(Point, f64)> = vertices
        .iter()
        .map(|&(x, y, b)| (Point::new(x as f64 / 100.0, y as f64 / 100.0), b as f64 / 128.0))
        .collect();
    let n = pts.len();
    let segs: Vec<Segment> = (0..n)
        .filter_map(|k| {
            let ((a, b), (e, _)) = (pts[k], pts[(k + 1) % n]);
            (a.distance(e) >= 1e-3).then(|| {
                Arc::from_bulge(a, e, b)
                    .map(Segment::Arc)
                    .unwrap_or(Segment::Line(Line::new(a, e)))
            })
        })
        .collect();
    Contour::new(segs)
}

fn counter_clockwise(c: Contour) -> Contour {
    if c.is_ccw() {
        c
    } else {
        c.reversed()
    }
}

/// The bulged polygon of the fuzz input, counter-clockwise.
fn outline(vertices: &[Vertex]) -> Contour {
    counter_clockwise(polygon(vertices))
}

/// The outline of the one pocket the importer finds in the bulged polygon taken in its own
/// direction, as the fuzz target takes it; `None` when it finds no pocket or several.
fn imported(vertices: &[Vertex]) -> Option<Contour> {
    let nesting = nesting_of(polygon(vertices)).ok()?;
    let [pocket] = &nesting.pockets[..] else {
        return None;
    };
    Some(counter_clockwise(pocket.boundary.clone()))
}

/// [`imported`], failing the test when the importer refuses.
fn imported_as_drawn(vertices: &[Vertex]) -> Contour {
    imported(vertices).expect("the importer takes the outline")
}

/// The table's one input that the importer takes only from some start vertices: the zigzag
/// of 0.01 mm steps is refused as crossing itself at (2.57, 2.565) from 107 of its 128 starts
/// and directions (a defect of the importer's self-crossing test, not of the offset).
const REFUSED_FROM_SOME_STARTS: &str =
    "two arcs 0.008 and 0.006 mm in radius turning back by 173° at a joint, d = 0.5";

/// The importer must take a drawn outline or refuse it whatever vertex it starts at and
/// whichever way round it is drawn. Today it does not: the zigzag above, and the two circles
/// drawn as semicircles touching at a neck (below), are refused as crossing themselves from
/// some starts. Resolving self-crossing and self-touching outlines instead of refusing them
/// (issue 17) is to make this pass; until then it is ignored, and fails when run.
#[test]
#[ignore = "the importer's self-crossing verdict depends on the start vertex (issue 17)"]
fn the_importers_verdict_does_not_depend_on_start_or_direction() {
    let zigzag = CASES
        .iter()
        .find(|c| c.note == REFUSED_FROM_SOME_STARTS)
        .expect("in the table");
    let circles: &[(i16, i16, i8)] = &[
        (21846, 16469, 0),
        (21845, 16469, -128),
        (21846, -6592, -128),
        (21846, -16299, -128),
        (21845, -6593, -128),
    ];
    for v in [zigzag.vertices, circles] {
        let verdicts: Vec<bool> = variants(v).iter().map(|(_, v)| imported(v).is_some()).collect();
        assert!(
            verdicts.iter().all(|&b| b == verdicts[0]),
            "taken from {} of {} starts and directions",
            verdicts.iter().filter(|&&b| b).count(),
            verdicts.len()
        );
    }
}

/// The importer's verdict on one contour.
fn nesting_of(contour: Contour) -> Result<pocketeer::import::Nesting, pocketeer::ImportError> {
    let tol = Tolerance::for_extent(&contour.bbox(), 0.001);
    let chained = pocketeer::import::ChainedContour {
        contour,
        layer: 0,
        elements: Vec::new(),
    };
    pocketeer::import::find_pockets(&[chained], &["0".to_string()], &tol)
}

/// The fuzz input's round islands that lie inside `boundary` and clear of it.
fn round_islands(boundary: &Contour, islands: &[(i16, i16, u8)]) -> Vec<Contour> {
    islands
        .iter()
        .map(|&(x, y, r)| {
            (
                Point::new(x as f64 / 100.0, y as f64 / 100.0),
                0.1 + r as f64 / 20.0,
            )
        })
        .filter(|&(c, r)| {
            boundary.contains(c) && boundary.segments.iter().all(|s| point_distance(s, c) > r + 0.01)
        })
        .map(|(c, r)| Contour::new(vec![Segment::Arc(Arc::new(c, r, 0.0, -std::f64::consts::TAU))]))
        .collect()
}

/// Outlines with a cusp (an element turning straight back) keep their one loop.
#[test]
fn big_bulge_outlines_keep_their_loop() {
    let a = [
        (3968, 3855, 15),
        (3855, 3855, 15),
        (3855, 100, 15),
        (31503, 31611, 123),
        (-17522, 3855, -15),
    ];
    let b = [
        (512, 0, 85),
        (21845, 21845, 85),
        (21852, 21845, 127),
        (15561, 25669, -97),
    ];
    for (label, v) in variants(&a) {
        let loops = check(
            &Pocket {
                boundary: outline(&v),
                islands: vec![],
            },
            990,
        );
        assert_eq!(loops.len(), 1, "{label}");
        // The outline's area is 158494 mm²; eroded by 1 mm along its 1.5 m of boundary.
        let area: f64 = loops.iter().map(Contour::signed_area).sum();
        assert!((150_000.0..158_494.0).contains(&area), "{label}: {area}");
    }
    for (label, v) in variants(&b) {
        let loops = check(
            &Pocket {
                boundary: outline(&v),
                islands: vec![],
            },
            4990,
        );
        assert_eq!(loops.len(), 1, "{label}");
    }
}

/// A needle 130 mm long whose two sides are flat arcs bulging the same way 0.01 mm apart: the
/// sides cross, and the importer refuses the outline with the place.
#[test]
fn a_hair_thin_needle_of_flat_arcs_crosses_itself_and_is_refused() {
    let v = [
        (-12851, 128, 0),
        (1535, -31996, -51),
        (-17715, -32564, -51),
        (-17235, -11603, -83),
        (-12849, -128, -1),
        (-12851, -13056, 1),
    ];
    for (label, v) in variants(&v) {
        match nesting_of(outline(&v)) {
            Err(pocketeer::ImportError::SelfCrossing { point, .. }) => assert!(
                (point.x + 127.995).abs() < 0.01 && (point.y + 64.64).abs() < 0.01,
                "{label}: {point:?}"
            ),
            other => panic!("{label}: expected a self-crossing refusal, got {other:?}"),
        }
    }
}

/// Three semicircles 0.02 mm across are a pocket, not a self-crossing.
#[test]
fn the_three_tiny_semicircles_are_a_pocket() {
    let v = [
        (-12850, 1261, -128),
        (-12852, 1261, -128),
        (-12852, 1263, -128),
        (-12862, -12851, 127),
    ];
    for (label, v) in variants(&v) {
        assert!(nesting_of(outline(&v)).is_ok(), "{label}");
    }
}

/// Two circles (radius 115.3 and 48.5) drawn as four semicircles touching at a neck 0.01 mm
/// wide. A line 1e-10 mm long pointing back against the arcs at the big circle's top (as an
/// importer may leave one) is a point to the raw offset: with it or without it, one loop in
/// each circle.
#[test]
fn a_line_shorter_than_rounding_pointing_back_is_a_point() {
    let v = [
        (21846, 16469, 0),
        (21845, 16469, -128),
        (21846, -6592, -128),
        (21846, -16299, -128),
        (21845, -6593, -128),
    ];
    for (label, v) in variants(&v) {
        // Refused from some starts: see `the_importers_verdict_does_not_depend_on_start_or_direction`.
        let Some(imported) = imported(&v).or_else(|| (label == DRAWN).then(|| imported_as_drawn(&v))) else {
            continue;
        };
        let top = imported
            .segments
            .iter()
            .map(Segment::end)
            .max_by(|a, b| a.y.total_cmp(&b.y))
            .expect("segments");
        let k = imported
            .segments
            .iter()
            .position(|s| s.end() == top)
            .expect("the top");
        let mut with_line = imported.segments.clone();
        with_line.insert(
            k + 1,
            Segment::Line(Line::new(top, Point::new(top.x + 1e-10, top.y))),
        );
        for boundary in [imported, Contour::new(with_line)] {
            let loops = check(
                &Pocket {
                    boundary,
                    islands: vec![],
                },
                21845,
            );
            // One loop in each circle: radius 115.31 - 21.855 and 48.53 - 21.855.
            assert_eq!(loops.len(), 2, "{label}");
            let area: f64 = loops.iter().map(Contour::signed_area).sum();
            let expected =
                std::f64::consts::PI * ((115.31f64 - 21.855).powi(2) + (48.53f64 - 21.855).powi(2));
            assert!(
                (area - expected).abs() < 2.0,
                "{label}: {area} against {expected}"
            );
        }
    }
}

/// The two circles joined by a neck 2.6 mm wide, a round island 0.2 mm across in the big one,
/// at d = 0.01: one loop round both circles and one round the island.
#[test]
fn a_line_shorter_than_rounding_beside_an_island() {
    let v = [
        (21846, 16469, 0),
        (21845, 16469, -128),
        (21846, -6337, -128),
        (21846, -16299, -128),
        (21845, -6593, -128),
    ];
    for (label, v) in variants(&v) {
        // Refused from some starts: see `the_importers_verdict_does_not_depend_on_start_or_direction`.
        let Some(boundary) = imported(&v).or_else(|| (label == DRAWN).then(|| imported_as_drawn(&v))) else {
            continue;
        };
        let island = Contour::new(vec![Segment::Arc(Arc::new(
            Point::new(218.45, 41.17),
            0.1,
            0.0,
            -std::f64::consts::TAU,
        ))]);
        assert!(boundary.contains(island.segments[0].start()), "{label}");
        let loops = check(
            &Pocket {
                boundary,
                islands: vec![island],
            },
            0,
        );
        assert_eq!(loops.len(), 2, "{label}");
        assert_eq!(
            loops.iter().filter(|l| l.signed_area() < 0.0).count(),
            1,
            "{label}"
        );
    }
}

/// Triangles whose inscribed circle has radius d to within 1e-9 (164 mm long and 0.02 high;
/// 5.1 mm long upright): nothing is left, and no loop runs round the outside through the walls.
#[test]
fn a_sliver_triangle_whose_inscribed_circle_has_radius_d() {
    for v in [
        [(24417, 0, 0), (8033, 0, 0), (16225, 2, 0)],
        [(257, 257, 0), (257, -255, 0), (255, 1, 0)],
    ] {
        for (label, v) in variants(&v) {
            let loops = check(
                &Pocket {
                    boundary: imported_as_drawn(&v),
                    islands: vec![],
                },
                0,
            );
            assert!(loops.is_empty(), "{label}: {loops:?}");
        }
    }
}

/// A lens 151 mm long and a sliver lens 1.3 mm long joined by a neck 0.0185 mm wide, narrower
/// than 2d = 0.02: only the big lens's loop, no loop at the neck.
#[test]
fn a_neck_narrower_than_2d_between_two_lenses() {
    let v = [(2, 131, 1), (-2, 0, 127), (14080, 5632, 0), (0, 0, 0)];
    for (label, v) in variants(&v) {
        let loops = check(
            &Pocket {
                boundary: imported_as_drawn(&v),
                islands: vec![],
            },
            0,
        );
        assert_eq!(loops.len(), 1, "{label}: {loops:?}");
        assert!(loops[0].is_ccw(), "{label}");
        assert!(loops[0].signed_area() > 8900.0, "{label}");
    }
}

/// A hairpin 327 mm long whose sides (a line and an arc bulging 0.02 mm from it) are 2d apart
/// to within 1e-7 mm at d = 0.01: the sides' offsets meet, and one loop is left, not a
/// clockwise loop through the walls.
#[test]
fn the_offsets_of_a_hairpin_2d_wide_meet() {
    let v = [(0, -32512, -17), (-255, 5888, 17), (-1, -255, -1), (-1, 255, 0)];
    for (label, v) in variants(&v) {
        let loops = check(
            &Pocket {
                boundary: imported_as_drawn(&v),
                islands: vec![],
            },
            0,
        );
        assert_eq!(loops.len(), 1, "{label}: {loops:?}");
        assert!(loops[0].is_ccw(), "{label}");
    }
}
