"""What issue 19's Python-side session (branch issue19py) added to the compat layer, against the lines Debian's
YADE 2023.02a printed for data/scripts/issue19py_features.py (`yade -n -x`, pasted below; run live too when
YADE is installed): A, YADE's `bf` clump-breakage functions (stressTensor in float32 with numpy 1.24's
roundings, checkFailure) on a standalone sphere and on clump members; B, yade.bodiesHandling
(spheresPackDimensions, facetsDimensions, spheresModify in place and as copies, sphereDuplicate); C, the
predicates inEllipsoid, inHyperboloid, inParallelepiped, notInNotch (YADE's quirks kept) on a grid with pads,
and a regularHexa packing clipped by them; D, O.bodies.getRoundness (with exclude lists) and clumpTemplate
(with its errors); E, the gts stand-in (sweptPolylines2gtsSurface with caps and cleanup, closedness, area,
volume), gts.read of YADE's horse.coarse.gts (data/gts) with translate/scale/rotate, and inGtsSurface on grids
kept off ties (a ray through an edge, which GTS breaks by memory addresses), with a pad and in regularHexa;
F, pack.hexaNet."""
from _scripts import needs_compat, needs_yade, tagged_lines, tagged_lines_both

YADE_LINES = [
    'A 0 [1, 5] [-120.55218505859375, 3.319753646850586, -5009.80224609375, 17.90353012084961, -45.090972900390625, -1765.4014892578125, -4367.595703125, -1192.09375, -233832.8125] [-53.97557830810547, -50.35074996948242, -3009.171142578125, -17.038192749023438, -16.922822952270508, -2815.40234375, -2699.673095703125, -2536.68359375, -183711.640625]',
    'A 0 95.22084404506683 46.78778333821297 0.0',
    'A 1 [0] [-112.61720275878906, -79.83063507080078, -5339.75927734375, 4.363437652587891, -12.633654594421387, 321.233642578125, -6105.59375, -4154.8544921875, -290756.78125] [-63.060577392578125, -63.67867660522461, -2852.05322265625, -20.553295135498047, -20.754751205444336, -929.56787109375, -3165.59423828125, -3196.622314453125, -143170.953125]',
    'A 1 106.537775 58.1728625 0.0',
    'A 2 [6] [-8547.3271484375, -26.838598251342773, -79645.8828125, -33.51690673828125, -0.10536698997020721, -311.8191833496094, -27239.14453125, -65.56635284423828, -334151.46875] [4.431241512298584, 6.533003807067871, -26189.51953125, 0.017292072996497154, 0.0254938006401062, -102.19959259033203, 27.699338912963867, 40.83728790283203, -163708.59375]',
    'A 2 97.05541250004006 68.13668750000174 0.0',
    "B [('center', (0.01975039867911954, 0.0007204274754275646, 0.024915612076663683)), ('extends', (0.060847683374733924, 0.02132330362265756, 0.05041779632236894)), ('mass', 0.023262865281301705), ('max', (0.0501742403664865, 0.011382079286756344, 0.050124510237848155)), ('maxId', (4.0, 4.0, 2.0)), ('min', (-0.010673443008247421, -0.009941224335901215, -0.00029328608452078644)), ('minId', (0.0, 0.0, 0.0)), ('number', 4), ('volume', 8.947255877423729e-06)]",
    'B 1 3 Not enough bodies to analyze with given mask',
    "B [('center', (0.12499999999999999, 0.05000000000000002, 0.04500000000000004)), ('extends', (0.35, 0.30000000000000004, 0.51)), ('max', (0.3, 0.2, 0.3)), ('maxId', (8.0, 7.0, 7.0)), ('min', (-0.05, -0.1, -0.20999999999999996)), ('minId', (7.0, 8.0, 8.0)), ('number', 2)]",
    'B (0.022577982290257273, 0.19393510297561406, -0.2789666953940503) 0.006999999999999999 0.0037355631046285032 (7.321703685071865e-08, 7.321703685071865e-08, 7.321703685071865e-08) 1 True',
    'B (0.042780871995766946, 0.2117772490334108, -0.29911222321306574) 0.0028 0.00023907603869622416 (7.497424573513589e-10, 7.497424573513589e-10, 7.497424573513589e-10) 6 True',
    'B True',
    'B (0.046174240366486506, 0.008382079286756343, 0.017616469565653825) 0.005200000000000001 0.0015313412740979727 (1.6562987220643675e-08, 1.6562987220643675e-08, 1.6562987220643675e-08)',
    'B 2 False',
    'C inEllipsoid 0 1312 2857280334',
    'C inEllipsoid 0.05 1039 4102864332',
    'C inEllipsoid -0.03 1499 3137506924',
    'C inEllipsoid [(-0.9, -0.8999999999999999, -0.4), (1.1, 0.49999999999999994, 0.5)]',
    'C inHyperboloid 0 2760 119902406',
    'C inHyperboloid 0.05 2132 3752312512',
    'C inHyperboloid -0.03 3218 3846352039',
    'C inHyperboloid [(-0.8955445270895245, -0.8988882021697693, -1.1), (1.0955445270895245, 0.9988882021697693, 1.1)]',
    'C inParallelepiped 0 725 2101701862',
    'C inParallelepiped 0.05 502 593667683',
    'C inParallelepiped -0.03 877 3234334088',
    'C inParallelepiped [(0.0, -0.2, 0.0), (1.3, 1.0, 0.9)]',
    'C notInNotch 0 12065 2015286715',
    'C notInNotch 0.05 11745 94902621',
    'C notInNotch -0.03 12240 3861958663',
    'C notInNotch [(-inf, -inf, -inf), (inf, inf, inf)]',
    'C 848 (-0.2385, -0.04613615326096476, -0.08261820090981617) (0.2740000000000001, 0.013042249330971922, 0.01781087854429414)',
    'D 0.8811788325207747 0.9384664010638033 0.8649136632685436',
    'D 2 [1, 0.5] [[0, 0, 0], [0.7, 0, 0]]',
    'D One or more of given lists for relative radii have length < 2! Given lists does not match clump template structure.',
    'D Two or more of given lists for relative positions are equal! Given lists does not match clump template structure.',
    'D One or more of given lists for relative positions do not have length of 3! Given lists does not match clump template structure.',
    'D Given lists must have same length! Given lists does not match clump template structure.',
    'E 38 21 57 True 13.7674556356 3.97144332044',
    'E [(-1.1712595282731448, -1.2674062858363708, 0.0), (1.3, 1.2674062858363708, 1.2)]',
    'E 0 2053 1274785721',
    'E 0.1 1513 1072516478',
    'E 512 True',
    'E False Surface is not closed.',
    'F True True 12 0.16 0.115 [(0.1, -0.085, 0.3), (0.26, -0.085, 0.3), (0.1, -0.2, 0.3)] (0.22000000000000003, -0.08499999999999999, 0.3)',
    'F True True 16 0.16 0.19 [(0.1, -0.2, 0.3), (0.1, -0.16, 0.3), (0.18, -0.2, 0.3)] (0.26, -0.009999999999999988, 0.3)',
    'F True False 14 0.2 0.115 [(0.1, -0.085, 0.3), (0.30000000000000004, -0.2, 0.3), (0.1, -0.2, 0.3)] (0.30000000000000004, -0.08499999999999999, 0.3)',
    'F True False 20 0.2 0.19 [(0.30000000000000004, -0.2, 0.3), (0.30000000000000004, -0.010000000000000009, 0.3), (0.1, -0.2, 0.3)] (0.26, -0.009999999999999988, 0.3)',
    'F False True 12 0.16 0.115 [(0.1, -0.2, 0.3), (0.26, -0.2, 0.3), (0.14, -0.2, 0.3)] (0.26, -0.08499999999999999, 0.3)',
    'F False True 18 0.16 0.19 [(0.1, -0.2, 0.3), (0.1, -0.010000000000000009, 0.3), (0.26, -0.2, 0.3)] (0.22000000000000003, -0.009999999999999988, 0.3)',
    'F False False 14 0.2 0.115 [(0.1, -0.2, 0.3), (0.30000000000000004, -0.085, 0.3), (0.14, -0.2, 0.3)] (0.26, -0.08499999999999999, 0.3)',
    'F False False 20 0.2 0.19 [(0.1, -0.2, 0.3), (0.1, -0.010000000000000009, 0.3), (0.14, -0.2, 0.3)] (0.30000000000000004, -0.009999999999999988, 0.3)',
    'E 336 1002 668 True 0.0369850928649 0.00026341826018',
    'E (-0.09183540871106224, -0.15608910643397197, 0.00435352629370447) (0.14657311888920388, 0.07671718077232895, 0.18511793431664011)',
    'E 99 80 3183468544',
    "E ['336', '1002', '668', 'GtsSurface', 'GtsFace', 'GtsEdge', 'GtsVertex']",
]


@needs_compat
def test_issue19py_features_equal_yade(tmp_path):
    assert tagged_lines('ryade', 'issue19py_features.py', [str(tmp_path)]) == YADE_LINES


@needs_compat
@needs_yade
def test_issue19py_features_live_yade(tmp_path):
    ryade, yade = tagged_lines_both('issue19py_features.py', tmp_path, 'ABCDEF')
    assert ryade == yade
