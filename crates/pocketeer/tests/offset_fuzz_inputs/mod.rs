//! The inputs of `offset_fuzz_regressions`: what the `offset` fuzz target found, with a
//! one-line note on what each exercises.

/// How the fuzz target takes a polygon.
#[derive(Clone, Copy, Debug)]
pub enum Take {
    /// As drawn, turned counter-clockwise.
    Outline,
    /// Through the importer (which cuts away sliver loops), as the target takes it now.
    Imported,
}

/// One input: the polygon, round islands (x, y in hundredths, radius 0.1 + r/20 mm) and the
/// distance (0.01 + distance/1000 mm).
pub struct Case {
    pub note: &'static str,
    pub take: Take,
    pub vertices: &'static [(i16, i16, i8)],
    pub islands: &'static [(i16, i16, u8)],
    pub distance: u16,
}

pub const CASES: &[Case] = &[
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
