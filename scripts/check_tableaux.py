#!/usr/bin/env python3
"""Independent verification of odyn's Tsit5 and DOP853 Butcher tableaux.

Reads the Rust constants from runtime/src/integrators/tableaux/{tsit5,dop853}.rs and checks them in three ways:

  1. Fidelity: every Rust literal is the correctly rounded f64 of the published high-precision
     value (the decimal strings in SOURCES below, extracted verbatim from the sources cited in
     the tableau files' headers). DOP853 is also compared with SciPy's port (scipy.integrate._ivp.
     dop853_coefficients) and Tsit5 with OrdinaryDiffEq.jl's own Float64 literals (both
     reported in units in the last place).
  2. Algebra: the order conditions, one per rooted tree, in 50-digit arithmetic applied to the
     exact binary values of the f64 constants: row sums, b (order 5 / 8), the embedded weights,
     and the dense output weights b(θ) at several θ.
  3. Numerics: each method implemented here in plain Python (mpmath, 40 digits, fixed step),
     on y' = y·cos t (exact exp(sin t)), the 2-D problem y1' = 2t·y1·log y2,
     y2' = −2t·y2·log y1 (exact exp(sin t²), exp(cos t²)) and the Kepler problem with
     eccentricity 0.5 (exact through Kepler's equation): observed global order, local error
     order, order of the error estimators and of the dense output's local error at θ = 0.5
     (and its maximum over θ).

Usage:  python3 scripts/check_tableaux.py          (about 10 s; not part of CI)
Exit status 0 iff every check passes. Needs mpmath; numpy/scipy only for the SciPy comparison.
"""

import ast
import math
import os
import re
import struct
import sys

import mpmath as mp

HERE = os.path.dirname(os.path.abspath(__file__))

# ---------------------------------------------------------------------------------------------
# Published values, as decimal strings (data, copied programmatically from the cited files).
#   "dop853": the PARAMETER statements of E. Hairer's dop853.f (D exponents written as e).
#   "tsit5": OrdinaryDiffEq.jl, lib/OrdinaryDiffEqTsit5/src/tsit_tableaus.jl, BigFloat method
#            (OrdinaryDiffEq numbering: cK is the node of stage K+1; "btilde" = b̂ − b there;
#             "bhatK" are the commented-out embedded 4th-order weights b̂_K).
#   "tsit5_odeq_f64": the same file's Float64 literals (Tsit5ConstantCacheActual and Tsit5Interp).
# ---------------------------------------------------------------------------------------------
SOURCES = {
    'dop853': {
        'c2': '0.526001519587677318785587544488e-01',
        'c3': '0.789002279381515978178381316732e-01',
        'c4': '0.118350341907227396726757197510e+00',
        'c5': '0.281649658092772603273242802490e+00',
        'c6': '0.333333333333333333333333333333e+00',
        'c7': '0.25e+00',
        'c8': '0.307692307692307692307692307692e+00',
        'c9': '0.651282051282051282051282051282e+00',
        'c10': '0.6e+00',
        'c11': '0.857142857142857142857142857142e+00',
        'c14': '0.1e+00',
        'c15': '0.2e+00',
        'c16': '0.777777777777777777777777777778e+00',
        'b1': '5.42937341165687622380535766363e-2',
        'b6': '4.45031289275240888144113950566e0',
        'b7': '1.89151789931450038304281599044e0',
        'b8': '-5.8012039600105847814672114227e0',
        'b9': '3.1116436695781989440891606237e-1',
        'b10': '-1.52160949662516078556178806805e-1',
        'b11': '2.01365400804030348374776537501e-1',
        'b12': '4.47106157277725905176885569043e-2',
        'bhh1': '0.244094488188976377952755905512e+00',
        'bhh2': '0.733846688281611857341361741547e+00',
        'bhh3': '0.220588235294117647058823529412e-01',
        'er1': '0.1312004499419488073250102996e-01',
        'er6': '-0.1225156446376204440720569753e+01',
        'er7': '-0.4957589496572501915214079952e+00',
        'er8': '0.1664377182454986536961530415e+01',
        'er9': '-0.3503288487499736816886487290e+00',
        'er10': '0.3341791187130174790297318841e+00',
        'er11': '0.8192320648511571246570742613e-01',
        'er12': '-0.2235530786388629525884427845e-01',
        'a21': '5.26001519587677318785587544488e-2',
        'a31': '1.97250569845378994544595329183e-2',
        'a32': '5.91751709536136983633785987549e-2',
        'a41': '2.95875854768068491816892993775e-2',
        'a43': '8.87627564304205475450678981324e-2',
        'a51': '2.41365134159266685502369798665e-1',
        'a53': '-8.84549479328286085344864962717e-1',
        'a54': '9.24834003261792003115737966543e-1',
        'a61': '3.7037037037037037037037037037e-2',
        'a64': '1.70828608729473871279604482173e-1',
        'a65': '1.25467687566822425016691814123e-1',
        'a71': '3.7109375e-2',
        'a74': '1.70252211019544039314978060272e-1',
        'a75': '6.02165389804559606850219397283e-2',
        'a76': '-1.7578125e-2',
        'a81': '3.70920001185047927108779319836e-2',
        'a84': '1.70383925712239993810214054705e-1',
        'a85': '1.07262030446373284651809199168e-1',
        'a86': '-1.53194377486244017527936158236e-2',
        'a87': '8.27378916381402288758473766002e-3',
        'a91': '6.24110958716075717114429577812e-1',
        'a94': '-3.36089262944694129406857109825e0',
        'a95': '-8.68219346841726006818189891453e-1',
        'a96': '2.75920996994467083049415600797e1',
        'a97': '2.01540675504778934086186788979e1',
        'a98': '-4.34898841810699588477366255144e1',
        'a101': '4.77662536438264365890433908527e-1',
        'a104': '-2.48811461997166764192642586468e0',
        'a105': '-5.90290826836842996371446475743e-1',
        'a106': '2.12300514481811942347288949897e1',
        'a107': '1.52792336328824235832596922938e1',
        'a108': '-3.32882109689848629194453265587e1',
        'a109': '-2.03312017085086261358222928593e-2',
        'a111': '-9.3714243008598732571704021658e-1',
        'a114': '5.18637242884406370830023853209e0',
        'a115': '1.09143734899672957818500254654e0',
        'a116': '-8.14978701074692612513997267357e0',
        'a117': '-1.85200656599969598641566180701e1',
        'a118': '2.27394870993505042818970056734e1',
        'a119': '2.49360555267965238987089396762e0',
        'a1110': '-3.0467644718982195003823669022e0',
        'a121': '2.27331014751653820792359768449e0',
        'a124': '-1.05344954667372501984066689879e1',
        'a125': '-2.00087205822486249909675718444e0',
        'a126': '-1.79589318631187989172765950534e1',
        'a127': '2.79488845294199600508499808837e1',
        'a128': '-2.85899827713502369474065508674e0',
        'a129': '-8.87285693353062954433549289258e0',
        'a1210': '1.23605671757943030647266201528e1',
        'a1211': '6.43392746015763530355970484046e-1',
        'a141': '5.61675022830479523392909219681e-2',
        'a147': '2.53500210216624811088794765333e-1',
        'a148': '-2.46239037470802489917441475441e-1',
        'a149': '-1.24191423263816360469010140626e-1',
        'a1410': '1.5329179827876569731206322685e-1',
        'a1411': '8.20105229563468988491666602057e-3',
        'a1412': '7.56789766054569976138603589584e-3',
        'a1413': '-8.298e-3',
        'a151': '3.18346481635021405060768473261e-2',
        'a156': '2.83009096723667755288322961402e-2',
        'a157': '5.35419883074385676223797384372e-2',
        'a158': '-5.49237485713909884646569340306e-2',
        'a1511': '-1.08347328697249322858509316994e-4',
        'a1512': '3.82571090835658412954920192323e-4',
        'a1513': '-3.40465008687404560802977114492e-4',
        'a1514': '1.41312443674632500278074618366e-1',
        'a161': '-4.28896301583791923408573538692e-1',
        'a166': '-4.69762141536116384314449447206e0',
        'a167': '7.68342119606259904184240953878e0',
        'a168': '4.06898981839711007970213554331e0',
        'a169': '3.56727187455281109270669543021e-1',
        'a1613': '-1.39902416515901462129418009734e-3',
        'a1614': '2.9475147891527723389556272149e0',
        'a1615': '-9.15095847217987001081870187138e0',
        'd41': '-0.84289382761090128651353491142e+01',
        'd46': '0.56671495351937776962531783590e+00',
        'd47': '-0.30689499459498916912797304727e+01',
        'd48': '0.23846676565120698287728149680e+01',
        'd49': '0.21170345824450282767155149946e+01',
        'd410': '-0.87139158377797299206789907490e+00',
        'd411': '0.22404374302607882758541771650e+01',
        'd412': '0.63157877876946881815570249290e+00',
        'd413': '-0.88990336451333310820698117400e-01',
        'd414': '0.18148505520854727256656404962e+02',
        'd415': '-0.91946323924783554000451984436e+01',
        'd416': '-0.44360363875948939664310572000e+01',
        'd51': '0.10427508642579134603413151009e+02',
        'd56': '0.24228349177525818288430175319e+03',
        'd57': '0.16520045171727028198505394887e+03',
        'd58': '-0.37454675472269020279518312152e+03',
        'd59': '-0.22113666853125306036270938578e+02',
        'd510': '0.77334326684722638389603898808e+01',
        'd511': '-0.30674084731089398182061213626e+02',
        'd512': '-0.93321305264302278729567221706e+01',
        'd513': '0.15697238121770843886131091075e+02',
        'd514': '-0.31139403219565177677282850411e+02',
        'd515': '-0.93529243588444783865713862664e+01',
        'd516': '0.35816841486394083752465898540e+02',
        'd61': '0.19985053242002433820987653617e+02',
        'd66': '-0.38703730874935176555105901742e+03',
        'd67': '-0.18917813819516756882830838328e+03',
        'd68': '0.52780815920542364900561016686e+03',
        'd69': '-0.11573902539959630126141871134e+02',
        'd610': '0.68812326946963000169666922661e+01',
        'd611': '-0.10006050966910838403183860980e+01',
        'd612': '0.77771377980534432092869265740e+00',
        'd613': '-0.27782057523535084065932004339e+01',
        'd614': '-0.60196695231264120758267380846e+02',
        'd615': '0.84320405506677161018159903784e+02',
        'd616': '0.11992291136182789328035130030e+02',
        'd71': '-0.25693933462703749003312586129e+02',
        'd76': '-0.15418974869023643374053993627e+03',
        'd77': '-0.23152937917604549567536039109e+03',
        'd78': '0.35763911791061412378285349910e+03',
        'd79': '0.93405324183624310003907691704e+02',
        'd710': '-0.37458323136451633156875139351e+02',
        'd711': '0.10409964950896230045147246184e+03',
        'd712': '0.29840293426660503123344363579e+02',
        'd713': '-0.43533456590011143754432175058e+02',
        'd714': '0.96324553959188282948394950600e+02',
        'd715': '-0.39177261675615439165231486172e+02',
        'd716': '-0.14972683625798562581422125276e+03',
    },
    'tsit5': {
        'c1': '161/1000',
        'c2': '327/1000',
        'c3': '9/10',
        'c4': '.9800255409045096857298102862870245954942137979563024768854764293221195950761080302604',
        'c5': '1',
        'c6': '1',
        'a21': '161/1000',
        'a31': '-.8480655492356988544426874250230774675121177393430391537369234245294192976164141156943e-2',
        'a32': '.3354806554923569885444268742502307746751211773934303915373692342452941929761641411569',
        'a41': '2.897153057105493432130432594192938764924887287701866490314866693455023795137503079289',
        'a42': '-6.359448489975074843148159912383825625952700647415626703305928850207288721235210244366',
        'a43': '4.362295432869581411017727318190886861027813359713760212991062156752264926097707165077',
        'a51': '5.325864828439256604428877920840511317836476253097040101202360397727981648835607691791',
        'a52': '-11.74888356406282787774717033978577296188744178259862899288666928009020615663593781589',
        'a53': '7.495539342889836208304604784564358155658679161518186721010132816213648793440552049753',
        'a54': '-.9249506636175524925650207933207191611349983406029535244034750452930469056411389539635e-1',
        'a61': '5.861455442946420028659251486982647890394337666164814434818157239052507339770711679748',
        'a62': '-12.92096931784710929170611868178335939541780751955743459166312250439928519268343184452',
        'a63': '8.159367898576158643180400794539253485181918321135053305748355423955009222648673734986',
        'a64': '-.7158497328140099722453054252582973869127213147363544882721139659546372402303777878835e-1',
        'a65': '-.2826905039406838290900305721271224146717633626879770007617876201276764571291579142206e-1',
        'a71': '.9646076681806522951816731316512876333711995238157997181903319145764851595234062815396e-1',
        'a72': '1/100',
        'a73': '.4798896504144995747752495322905965199130404621990332488332634944254542060153074523509',
        'a74': '1.379008574103741893192274821856872770756462643091360525934940067397245698027561293331',
        'a75': '-3.290069515436080679901047585711363850115683290894936158531296799594813811049925401677',
        'a76': '2.324710524099773982415355918398765796109060233222962411944060046314465391054716027841',
        'btilde1': '-1.780011052225771443378550607539534775944678804333659557637450799792588061629796e-03',
        'btilde2': '-8.164344596567469032236360633546862401862537590159047610940604670770447527463931e-04',
        'btilde3': '7.880878010261996010314727672526304238628733777103128603258129604952959142646516e-03',
        'btilde4': '-1.44711007173262907537165147972635116720922712343167677619514233896760819649515e-01',
        'btilde5': '5.823571654525552250199376106520421794260781239567387797673045438803694038950012e-01',
        'btilde6': '-4.580821059291869466616365188325542974428047279788398179474684434732070620889539e-01',
        'btilde7': '1/66',
        'bhat1': '.9468075576583945807478876255758922856117527357724631226139574065785592789071067303271e-1',
        'bhat2': '.9183565540343253096776363936645313759813746240984095238905939532922955247253608687270e-2',
        'bhat3': '.4877705284247615707855642599631228241516691959761363774365216240304071651579571959813',
        'bhat4': '1.234297566930478985655109673884237654035539930748192848315425833500484878378061439761',
        'bhat5': '-2.707712349983525454881109975059321670689605166938197378763992255714444407154902012702',
        'bhat6': '1.866628418170587035753719399566211498666255505244122593996591602841258328965767580089',
    },
    'tsit5_odeq_f64': {
        'c1': '0.161',
        'c2': '0.327',
        'c3': '0.9',
        'c4': '0.9800255409045097',
        'c5': '1',
        'c6': '1',
        'a21': '0.161',
        'a31': '-0.008480655492356989',
        'a32': '0.335480655492357',
        'a41': '2.8971530571054935',
        'a42': '-6.359448489975075',
        'a43': '4.3622954328695815',
        'a51': '5.325864828439257',
        'a52': '-11.748883564062828',
        'a53': '7.4955393428898365',
        'a54': '-0.09249506636175525',
        'a61': '5.86145544294642',
        'a62': '-12.92096931784711',
        'a63': '8.159367898576159',
        'a64': '-0.071584973281401',
        'a65': '-0.028269050394068383',
        'a71': '0.09646076681806523',
        'a72': '0.01',
        'a73': '0.4798896504144996',
        'a74': '1.379008574103742',
        'a75': '-3.290069515436081',
        'a76': '2.324710524099774',
        'btilde1': '-0.00178001105222577714',
        'btilde2': '-0.0008164344596567469',
        'btilde3': '0.007880878010261995',
        'btilde4': '-0.1447110071732629',
        'btilde5': '0.5823571654525552',
        'btilde6': '-0.45808210592918697',
        'btilde7': '0.015151515151515152',
        'r11': '1.0',
        'r12': '-2.763706197274826',
        'r13': '2.9132554618219126',
        'r14': '-1.0530884977290216',
        'r22': '0.13169999999999998',
        'r23': '-0.2234',
        'r24': '0.1017',
        'r32': '3.9302962368947516',
        'r33': '-5.941033872131505',
        'r34': '2.490627285651253',
        'r42': '-12.411077166933676',
        'r43': '30.33818863028232',
        'r44': '-16.548102889244902',
        'r52': '37.50931341651104',
        'r53': '-88.1789048947664',
        'r54': '47.37952196281928',
        'r62': '-27.896526289197286',
        'r63': '65.09189467479366',
        'r64': '-34.87065786149661',
        'r72': '1.5',
        'r73': '-4',
        'r74': '2.5',
    },
}

# Embedded 4th-order weights b̂ of Tsit5 to 40 digits, from SUNDIALS (llnl/sundials PR #850,
# src/arkode/arkode_butcher_erk.def, ARKODE_TSITOURAS_7_4_5), an independent cross-check.
SUNDIALS_TSIT5_BHAT = [
    "0.09468075576583945807478876255758922856118",
    "0.009183565540343253096776363936645313759814",
    "0.4877705284247615707855642599631228241517",
    "1.234297566930478985655109673884237654036",
    "-2.707712349983525454881109975059321670690",
    "1.866628418170587035753719399566211498666",
    "0.01515151515151515151515151515151515151515",
]

# Tsitouras (2011), continuous extension as printed in the paper (factored form), quoted in
# torchode (torchode/single_step_methods/tsit5.py); (scale, roots or quadratic factors).
TSIT5_PAPER_DENSE = [
    ("-1.0530884977290216", "t*(t-1.3299890189751412)*(t**2-1.4364028541716351*t+0.7139816917074209)"),
    ("0.1017", "t**2*(t**2-2.1966568338249754*t+1.2949852507374631)"),
    ("2.490627285651252793", "t**2*(t**2-2.38535645472061657*t+1.57803468208092486)"),
    ("-16.54810288924490272", "(t-1.21712927295533244)*(t-0.61620406037800089)*t**2"),
    ("47.37952196281928122", "(t-1.203071208372362603)*(t-0.658047292653547382)*t**2"),
    ("-34.87065786149660974", "(t-1.2)*(t-0.666666666666666667)*t**2"),
    ("2.5", "(t-1)*(t-0.6)*t**2"),
]

FAILURES = []
TINY = mp.mpf("1e-40")  # keeps 0/0 ratios (all-zero rows) at 0
DELTA = {}  # max order-condition residual of B per order, from section 2 (f64 rounding level)


def check(ok, what):
    print(("  ok    " if ok else "  FAIL  ") + what)
    if not ok:
        FAILURES.append(what)


# ---------------------------------------------------------------------------------------------
# Reading the Rust files
# ---------------------------------------------------------------------------------------------
def read_rust(path):
    """Returns {NAME: value} for every `pub(super) const NAME: T = value;` (nested lists)."""
    text = open(path, encoding="utf-8").read()
    text = re.sub(r"//[^\n]*", "", text)
    out = {}
    for m in re.finditer(r"pub\(super\)\s+const\s+(\w+)\s*:\s*([^=]+?)=\s*(.*?);", text, re.S):
        name, expr = m.group(1), m.group(3)
        out[name] = ast.literal_eval(expr)
    return out


def ulps(x, y):
    """Distance between two finite f64 in units in the last place."""
    def key(v):
        i = struct.unpack("<q", struct.pack("<d", v))[0]
        return i if i >= 0 else -(i & 0x7FFFFFFFFFFFFFFF)
    return abs(key(x) - key(y))


def f64(x):
    """Correctly rounded f64 of an mpf / decimal string."""
    if isinstance(x, str):
        return float(x)
    return float(x)  # mpmath rounds to nearest: a single rounding of the 60-digit value


def mpd(s):
    """Decimal string (possibly 'p/q') to mpf."""
    if "/" in s:
        p, q = s.split("/")
        return mp.mpf(p) / mp.mpf(q)
    return mp.mpf(s)


# ---------------------------------------------------------------------------------------------
# Rooted trees and elementary weights
# ---------------------------------------------------------------------------------------------
def trees_upto(n):
    def graft(t):
        out = [tuple(sorted(t + ((),)))]
        for i, ch in enumerate(t):
            for nc in graft(ch):
                out.append(tuple(sorted(t[:i] + (nc,) + t[i + 1:])))
        return out
    T = {1: [()]}
    for k in range(2, n + 1):
        T[k] = sorted({nt for t in T[k - 1] for nt in graft(t)})
    return T


def order(t):
    return 1 + sum(order(c) for c in t)


def gamma(t):
    g = order(t)
    for c in t:
        g *= gamma(c)
    return g


class Weights:
    """Memoised stage vectors g(t) with b·g(t) = 1/γ(t) being the order condition of tree t."""

    def __init__(self, A):
        self.A = [[mp.mpf(x) for x in row] for row in A]
        self.absA = [[abs(x) for x in row] for row in self.A]
        self.s = len(A)
        self.memo = {}

    def _g(self, t, A, key):
        if (t, key) not in self.memo:
            v = [mp.mpf(1)] * self.s
            for ch in t:
                gc = self._g(ch, A, key)
                Ag = [mp.fsum(a * x for a, x in zip(row, gc)) for row in A]
                v = [vi * ai for vi, ai in zip(v, Ag)]
            self.memo[(t, key)] = v
        return self.memo[(t, key)]

    def g(self, t):
        return self._g(t, self.A, 0)

    def residual(self, w, t, theta=1):
        w = [mp.mpf(x) for x in w]
        return mp.fsum(wi * gi for wi, gi in zip(w, self.g(t))) - mp.mpf(theta) ** order(t) / gamma(t)

    def rounding_bound(self, wabs, t, extra=1):
        """First-order bound on |Φ(t)| − its value for the unrounded coefficients when each
        coefficient carries a relative error ≤ u = 2⁻⁵³ (rounding to f64): each monomial of
        w·g(t) has |t| − 1 entries of A and `extra` factors from the weights."""
        u = mp.mpf(2) ** -53
        gabs = self._g(t, self.absA, 1)
        return (order(t) - 1 + extra) * u * mp.fsum(w * x for w, x in zip(wabs, gabs))

    def check_trees(self, w, trees, theta=1, wabs=None, extra=1):
        """(max |residual|, max residual/bound) over trees; a ratio ≤ 1 means the residual is
        fully explained by rounding the coefficients to f64."""
        wabs = wabs or [abs(mp.mpf(x)) for x in w]
        res = [abs(self.residual(w, t, theta)) for t in trees]
        ratio = [r / (self.rounding_bound(wabs, t, extra) + mp.mpf("1e-28")) for r, t in zip(res, trees)]
        return max(res), max(ratio)


def exact_binary(x):
    return mp.mpf(float(x))


# ---------------------------------------------------------------------------------------------
# High-precision reference tableaux from SOURCES
# ---------------------------------------------------------------------------------------------
def tsit5_reference():
    S = SOURCES["tsit5"]
    c = [mp.mpf(0)] + [mpd(S["c%d" % i]) for i in range(1, 7)]
    A = [[mp.mpf(0)] * 7 for _ in range(7)]
    for i in range(2, 8):
        for j in range(1, i):
            A[i - 1][j - 1] = mpd(S["a%d%d" % (i, j)])
    b = A[6][:6] + [mp.mpf(0)]
    btilde = [-mpd(S["btilde%d" % i]) for i in range(1, 8)]  # odyn: b − b̂ (OrdinaryDiffEq: b̂ − b)
    bhat = [bi - ei for bi, ei in zip(b, btilde)]
    return dict(c=c, A=A, b=b, btilde=btilde, bhat=bhat)


def tsit5_dense_reconstruct(A, b):
    """The unique degree-4 b_i(θ) (i = 1..7) with: b_i(θ) = O(θ²) for i ≥ 2 (b'(0) = e1),
    b(1) = b, b'(1) = e7 (C¹ at both ends, stage 7 being f(t+h, y₁)), the 8 order conditions
    of order ≤ 4 identically in θ, and r_{2,4} = 0.1017 (Tsitouras' one free parameter).
    Returns R[i][k-1] = coefficient of θ^k in b_i(θ)."""
    W = Weights(A)
    T = trees_upto(4)
    trees = [t for n in range(1, 5) for t in T[n]]
    rows, rhs = [], []

    def unit(j):
        return [mp.mpf(1) if i == j else mp.mpf(0) for i in range(7)]
    for k in (2, 3, 4):
        for t in trees:
            r = [mp.mpf(0)] * 21
            r[(k - 2) * 7:(k - 1) * 7] = W.g(t)
            rows.append(r)
            rhs.append(mp.mpf(1) / gamma(t) if order(t) == k else mp.mpf(0))
    for weights, target in (((1, 1, 1), [bi - ui for bi, ui in zip(b, unit(0))]),
                            ((2, 3, 4), [u7 - u1 for u7, u1 in zip(unit(6), unit(0))])):
        for i in range(7):
            r = [mp.mpf(0)] * 21
            for m, k in enumerate((2, 3, 4)):
                r[(k - 2) * 7 + i] = mp.mpf(weights[m])
            rows.append(r)
            rhs.append(target[i])
    r = [mp.mpf(0)] * 21
    r[2 * 7 + 1] = mp.mpf(1)
    rows.append(r)
    rhs.append(mp.mpf("0.1017"))
    M, y = mp.matrix(rows), mp.matrix(rhs)
    x = mp.lu_solve(M.T * M, M.T * y)
    resid = mp.norm(M * x - y)
    R = [[mp.mpf(1) if i == 0 else mp.mpf(0)] + [x[(k - 2) * 7 + i] for k in (2, 3, 4)] for i in range(7)]
    return R, resid


def dop853_reference():
    S = {k: mp.mpf(v) for k, v in SOURCES["dop853"].items()}
    c = [mp.mpf(0)] + [S["c%d" % i] for i in range(2, 12)] + [mp.mpf(1)]
    A = [[mp.mpf(0)] * 12 for _ in range(12)]
    for i in range(2, 13):
        for j in range(1, i):
            A[i - 1][j - 1] = S.get("a%d%d" % (i, j), mp.mpf(0))
    b = [S.get("b%d" % j, mp.mpf(0)) for j in range(1, 13)]
    bhh = [mp.mpf(0)] * 12
    bhh[0], bhh[8], bhh[11] = S["bhh1"], S["bhh2"], S["bhh3"]
    e5 = [S.get("er%d" % j, mp.mpf(0)) for j in range(1, 13)]
    e3 = [bj - hj for bj, hj in zip(b, bhh)]
    c_extra = [S["c14"], S["c15"], S["c16"]]
    a_extra = [[S.get("a%d%d" % (i, j), mp.mpf(0)) for j in range(1, 17)] for i in (14, 15, 16)]
    d = [[S.get("d%d%d" % (m, j), mp.mpf(0)) for j in range(1, 17)] for m in (4, 5, 6, 7)]
    return dict(c=c, A=A, b=b, bhh=bhh, e5=e5, e3=e3, c_extra=c_extra, a_extra=a_extra, d=d)


def dop853_extended(A, b, c_extra, a_extra):
    """16×16 matrix of the extended method: stages 1–12, stage 13 = f(t+h, y₁) (row = b),
    stages 14–16 of the dense output. Returns (A16, c16)."""
    A16 = [[mp.mpf(0)] * 16 for _ in range(16)]
    for i in range(12):
        for j in range(12):
            A16[i][j] = mp.mpf(A[i][j])
    for j in range(12):
        A16[12][j] = mp.mpf(b[j])
    for r in range(3):
        for j in range(16):
            A16[13 + r][j] = mp.mpf(a_extra[r][j])
    return A16


def dop853_dense_weights(b, d, theta, absolute=False):
    """Weights B(θ) over the 16 stages with u(θ) = y₀ + h·Σ B_j(θ)·k_j, equivalent to Hairer's
    CONTD8: u = r0 + θ(r1 + θ1(r2 + θ(r3 + θ1(r4 + θ(r5 + θ1(r6 + θ r7)))))), θ1 = 1 − θ.
    With absolute=True, the same expression with every coefficient and sign made positive (for
    rounding bounds)."""
    th = mp.mpf(theta)
    th1 = 1 - th
    sg = (lambda x: abs(x)) if absolute else (lambda x: x)
    neg = 1 if absolute else -1
    bb = [sg(mp.mpf(x)) for x in b] + [mp.mpf(0)] * 4
    e1 = [mp.mpf(1)] + [mp.mpf(0)] * 15
    e13 = [mp.mpf(0)] * 12 + [mp.mpf(1)] + [mp.mpf(0)] * 3
    r1 = bb
    r2 = [x + neg * y for x, y in zip(e1, bb)]
    r3 = [x + neg * y + neg * z for x, y, z in zip(bb, e13, r2)]
    r4, r5, r6, r7 = ([sg(mp.mpf(x)) for x in row] for row in d)
    out = []
    for j in range(16):
        conpar = r4[j] + th * (r5[j] + th1 * (r6[j] + th * r7[j]))
        out.append(th * (r1[j] + th1 * (r2[j] + th * (r3[j] + th1 * conpar))))
    return out


# ---------------------------------------------------------------------------------------------
# Test problems (exact solutions)
# ---------------------------------------------------------------------------------------------
class Growth:
    """Scalar, linear in y, non-autonomous. Its elementary differentials are special (scalar
    problems cannot separate all trees), so it only backs up the system problems below."""
    name = "y' = y·cos t (scalar)"
    t0, t1 = mp.mpf(0), mp.mpf(4)
    system = False
    # fixed-step counts for the global order, first step of the local runs (h = h0·2^-k)
    grid = {"Tsit5": [8, 16, 32, 64], "DOP853": [4, 8, 16, 32]}
    h0 = {"Tsit5": "0.4", "DOP853": "0.8"}

    @staticmethod
    def f(t, y):
        return [y[0] * mp.cos(t)]

    @staticmethod
    def exact(t):
        return [mp.exp(mp.sin(t))]


class Hnw2d:
    """2-D, nonlinear, non-autonomous: y1' = 2t·y1·log y2, y2' = −2t·y2·log y1, exact
    y1 = exp(sin t²), y2 = exp(cos t²) (the test problem of Hairer–Nørsett–Wanner, Vol. I)."""
    name = "2-D exp(sin t²), exp(cos t²)"
    t0, t1 = mp.mpf(0), mp.mpf(2)
    system = True
    grid = {"Tsit5": [16, 32, 64, 128, 256], "DOP853": [8, 16, 32, 64]}
    h0 = {"Tsit5": "0.2", "DOP853": "0.2"}

    @staticmethod
    def f(t, y):
        return [2 * t * y[0] * mp.log(y[1]), -2 * t * y[1] * mp.log(y[0])]

    @staticmethod
    def exact(t):
        return [mp.exp(mp.sin(t * t)), mp.exp(mp.cos(t * t))]


class Kepler:
    """4-D, nonlinear: the Kepler problem q'' = −q/|q|³ with eccentricity 0.5 over one period,
    from perihelion; exact solution through Kepler's equation E − e·sin E = t."""
    name = "Kepler, e = 0.5"
    ecc = mp.mpf("0.5")
    t0, t1 = mp.mpf(0), mp.mpf(2) * mp.pi
    system = True
    grid = {"Tsit5": [32, 64, 128, 256, 512], "DOP853": [32, 64, 128, 256]}
    h0 = {"Tsit5": "0.2", "DOP853": "0.2"}

    @staticmethod
    def f(t, y):
        q1, q2, p1, p2 = y
        r3 = (q1 * q1 + q2 * q2) ** mp.mpf(1.5)
        return [p1, p2, -q1 / r3, -q2 / r3]

    @classmethod
    def exact(cls, t):
        e = cls.ecc
        E = mp.findroot(lambda E: E - e * mp.sin(E) - t, t)
        den = 1 - e * mp.cos(E)
        s = mp.sqrt(1 - e * e)
        return [mp.cos(E) - e, s * mp.sin(E), -mp.sin(E) / den, s * mp.cos(E) / den]


PROBLEMS = (Growth, Hnw2d, Kepler)


def axpy(y, h, ws, ks):
    out = list(y)
    for w, k in zip(ws, ks):
        if w != 0:
            hw = h * w
            out = [o + hw * ki for o, ki in zip(out, k)]
    return out


def err(u, v):
    return max(abs(a - b) for a, b in zip(u, v))


# ---------------------------------------------------------------------------------------------
# The two methods, fixed step, plain Python
# ---------------------------------------------------------------------------------------------
class Tsit5:
    name = "Tsit5"

    def __init__(self, T):
        self.c = [mp.mpf(x) for x in T["C"]]
        self.A = [[mp.mpf(x) for x in row] for row in T["A"]]
        self.b = [mp.mpf(x) for x in T["B"]]
        self.bt = [mp.mpf(x) for x in T["BTILDE"]]
        self.R = [[mp.mpf(x) for x in row] for row in T["DENSE"]]

    def step(self, f, t, y, h):
        ks = []
        for i in range(7):
            yi = axpy(y, h, self.A[i][:i], ks)
            ks.append(f(t + self.c[i] * h, yi))
        y1 = axpy(y, h, self.b, ks)
        est = [h * mp.fsum(w * k[n] for w, k in zip(self.bt, ks)) for n in range(len(y))]
        return y1, ks, {"btilde": est}

    def dense(self, y, h, ks, theta):
        th = mp.mpf(theta)
        w = [th * (r[0] + th * (r[1] + th * (r[2] + th * r[3]))) for r in self.R]
        return axpy(y, h, w, ks)


class Dop853:
    name = "DOP853"

    def __init__(self, T):
        self.c = [mp.mpf(x) for x in T["C"]]
        self.A = [[mp.mpf(x) for x in row] for row in T["A"]]
        self.b = [mp.mpf(x) for x in T["B"]]
        self.e5 = [mp.mpf(x) for x in T["E5"]]
        self.e3 = [mp.mpf(x) for x in T["E3"]]
        self.cx = [mp.mpf(x) for x in T["C_EXTRA"]]
        self.ax = [[mp.mpf(x) for x in row] for row in T["A_EXTRA"]]
        self.d = [[mp.mpf(x) for x in row] for row in T["D"]]

    def step(self, f, t, y, h):
        ks = []
        for i in range(12):
            yi = axpy(y, h, self.A[i][:i], ks)
            ks.append(f(t + self.c[i] * h, yi))
        y1 = axpy(y, h, self.b, ks)
        e5 = [h * mp.fsum(w * k[n] for w, k in zip(self.e5, ks)) for n in range(len(y))]
        e3 = [h * mp.fsum(w * k[n] for w, k in zip(self.e3, ks)) for n in range(len(y))]
        # Hairer's combination with sk = 1 (pure absolute scaling), RMS norms
        n5 = mp.fsum(x * x for x in e5) / len(y)
        n3 = mp.fsum(x * x for x in e3) / len(y)
        comb = n5 / mp.sqrt(n5 + mp.mpf("0.01") * n3)
        return y1, ks, {"E5": e5, "E3": e3, "hairer": [comb]}

    def dense(self, y, h, ks, theta, t=None, f=None, y1=None):
        ks = list(ks)
        ks.append(f(t + h, y1))  # stage 13: f(t+h, y1)
        for r in range(3):
            yi = axpy(y, h, self.ax[r][:13 + r], ks)
            ks.append(f(t + self.cx[r] * h, yi))
        th = mp.mpf(theta)
        th1 = 1 - th
        out = []
        for n in range(len(y)):
            ydiff = y1[n] - y[n]
            bspl = h * ks[0][n] - ydiff
            r = [y[n], ydiff, bspl, ydiff - h * ks[12][n] - bspl]
            r += [h * mp.fsum(w * k[n] for w, k in zip(row, ks)) for row in self.d]
            conpar = r[4] + th * (r[5] + th1 * (r[6] + th * r[7]))
            out.append(r[0] + th * (r[1] + th1 * (r[2] + th * (r[3] + th1 * conpar))))
        return out


def dense_eval(method, f, t, y, h, ks, y1, theta):
    if isinstance(method, Dop853):
        return method.dense(y, h, ks, theta, t=t, f=f, y1=y1)
    return method.dense(y, h, ks, theta)


def slopes(hs, es):
    return [math.log(float(es[i] / es[i + 1])) / math.log(float(hs[i] / hs[i + 1])) for i in range(len(es) - 1)]


# ---------------------------------------------------------------------------------------------
# 1. Fidelity
# ---------------------------------------------------------------------------------------------
def fidelity(ts, dp):
    print("\n== 1. Literal fidelity (Rust literal == correctly rounded published value) ==")
    ref = tsit5_reference()
    bad = []
    for i in range(7):
        if f64(ref["c"][i]) != ts["C"][i]:
            bad.append("C[%d]" % i)
        for j in range(7):
            if f64(ref["A"][i][j]) != ts["A"][i][j]:
                bad.append("A[%d][%d]" % (i, j))
        if f64(ref["b"][i]) != ts["B"][i]:
            bad.append("B[%d]" % i)
        if f64(ref["btilde"][i]) != ts["BTILDE"][i]:
            bad.append("BTILDE[%d]" % i)
    check(not bad, "Tsit5 C, A, B, BTILDE: 7+49+7+7 literals equal the rounded OrdinaryDiffEq BigFloat values %s" % (bad or ""))
    sund = [mp.mpf(x) for x in SUNDIALS_TSIT5_BHAT]
    dev = max(abs(x - y) for x, y in zip(ref["bhat"], sund))
    check(dev < mp.mpf("1e-39"), "Tsit5 b̂ = b − BTILDE agrees with SUNDIALS' 40-digit b̂ (max diff %s)" % mp.nstr(dev, 3))
    R, resid = tsit5_dense_reconstruct(ref["A"], ref["b"])
    check(resid < mp.mpf("1e-40"), "Tsit5 dense: the conditions defining b_i(θ) are consistent (residual %s)" % mp.nstr(resid, 3))
    badd = [(i, k) for i in range(7) for k in range(4) if f64(R[i][k]) != ts["DENSE"][i][k]]
    check(not badd, "Tsit5 DENSE: 28 literals equal the rounded 60-digit reconstruction %s" % (badd or ""))
    worst = mp.mpf(0)
    for i, (scale, expr) in enumerate(TSIT5_PAPER_DENSE):
        # numbers as exact decimals (mpf of the printed string), not Python binary floats
        expr_mp = re.sub(r"(\d+\.\d+|\d+)", lambda m: "mpf('%s')" % m.group(1), expr)
        expr_mp = expr_mp.replace("**mpf('2')", "**2")
        pc = mp.taylor(lambda tt: mp.mpf(scale) * eval(expr_mp, {"mpf": mp.mpf}, {"t": tt}), 0, 4)
        for k in range(4):
            rel = abs(pc[k + 1] - R[i][k]) / max(abs(R[i][k]), 1)
            worst = max(worst, rel)
    check(worst < mp.mpf("1e-16"), "Tsit5 DENSE agrees with the paper's printed (factored) b_i(θ) to all printed digits (max rel diff %s)" % mp.nstr(worst, 3))
    F = SOURCES["tsit5_odeq_f64"]
    diffs = {}
    for i in range(1, 7):
        diffs["c%d" % (i + 1)] = ulps(float(F["c%d" % i]), ts["C"][i])
    for i in range(2, 8):
        for j in range(1, i):
            diffs["a%d%d" % (i, j)] = ulps(float(F["a%d%d" % (i, j)]), ts["A"][i - 1][j - 1])
    for i in range(1, 8):
        diffs["btilde%d" % i] = ulps(-float(F["btilde%d" % i]), ts["BTILDE"][i - 1])
    for i in range(1, 8):
        for k in range(1, 5):
            key = "r%d%d" % (i, k)
            if key in F:
                diffs[key] = ulps(float(F[key]), ts["DENSE"][i - 1][k - 1])
    nz = {k: v for k, v in diffs.items() if v}
    print("    info: OrdinaryDiffEq.jl Float64 literals vs odyn, in ulps (only nonzero): %s" % (nz or "none"))
    # OrdinaryDiffEq's Float64 btilde1 literal, -0.00178001105222577714, has one digit too many
    # against its own BigFloat value -0.0017800110522257714433...: a 5.7e-18 (26 ulp) slip there.
    others = [v for k, v in diffs.items() if k != "btilde1"]
    check(max(others) <= 1, "Tsit5 agrees with OrdinaryDiffEq.jl's Float64 literals to <= 1 ulp "
          "(except its btilde1 literal, which is off its own BigFloat value by %d ulp)" % diffs["btilde1"])

    ref8 = dop853_reference()
    bad = []
    for i in range(12):
        if f64(ref8["c"][i]) != dp["C"][i]:
            bad.append("C[%d]" % i)
        for j in range(12):
            if f64(ref8["A"][i][j]) != dp["A"][i][j]:
                bad.append("A[%d][%d]" % (i, j))
        for key, name in (("b", "B"), ("e5", "E5"), ("e3", "E3")):
            if f64(ref8[key][i]) != dp[name][i]:
                bad.append("%s[%d]" % (name, i))
    for r in range(3):
        if f64(ref8["c_extra"][r]) != dp["C_EXTRA"][r]:
            bad.append("C_EXTRA[%d]" % r)
        for j in range(16):
            if f64(ref8["a_extra"][r][j]) != dp["A_EXTRA"][r][j]:
                bad.append("A_EXTRA[%d][%d]" % (r, j))
    for m in range(4):
        for j in range(16):
            if f64(ref8["d"][m][j]) != dp["D"][m][j]:
                bad.append("D[%d][%d]" % (m, j))
    check(not bad, "DOP853 C, A, B, E5, E3, C_EXTRA, A_EXTRA, D equal the rounded dop853.f values %s" % (bad or ""))
    try:
        from scipy.integrate._ivp import dop853_coefficients as sc
    except Exception as exc:  # pragma: no cover
        print("    (SciPy not available: %s)" % exc)
        return
    diffs = {}
    for i in range(16):
        cc = dp["C"][i] if i < 12 else (1.0 if i == 12 else dp["C_EXTRA"][i - 13])
        diffs["C[%d]" % i] = ulps(cc, float(sc.C[i]))
        for j in range(16):
            if i < 12:
                mine = dp["A"][i][j] if j < 12 else 0.0
            elif i == 12:
                mine = dp["B"][j] if j < 12 else 0.0
            else:
                mine = dp["A_EXTRA"][i - 13][j]
            diffs["A[%d][%d]" % (i, j)] = ulps(mine, float(sc.A[i, j]))
    for j in range(12):
        diffs["B[%d]" % j] = ulps(dp["B"][j], float(sc.B[j]))
        diffs["E5[%d]" % j] = ulps(dp["E5"][j], float(sc.E5[j]))
        diffs["E3[%d]" % j] = ulps(dp["E3"][j], float(sc.E3[j]))
    for m in range(4):
        for j in range(16):
            diffs["D[%d][%d]" % (m, j)] = ulps(dp["D"][m][j], float(sc.D[m, j]))
    nz = {k: v for k, v in diffs.items() if v}
    print("    info: SciPy dop853_coefficients vs odyn, in ulps (only nonzero): %s" % (nz or "none"))
    check(all(v == 0 for k, v in diffs.items() if not k.startswith("E3")) and max(diffs.values()) <= 1,
          "DOP853 bitwise equal to SciPy's port (E3 within 1 ulp: SciPy subtracts bhh in f64)")


# ---------------------------------------------------------------------------------------------
# 2. Algebraic order conditions
# ---------------------------------------------------------------------------------------------
def algebra(ts, dp):
    print("\n== 2. Order conditions (all rooted trees; exact binary values of the f64 literals) ==")
    print("   Each residual Φ(t) − θ^|t|/γ(t) is compared with a first-order bound of what rounding")
    print("   every coefficient to f64 can cause (|t|·u·Σ|w|·|A|…|A|·1, u = 2^-53): 'ratio' ≤ 1 means")
    print("   the condition holds exactly up to that rounding; the next order must fail by far more.")
    mp.mp.dps = 50
    T = trees_upto(9)
    u = mp.mpf(2) ** -53

    def table(label, W, w, orders, theta=1, wabs=None, extra=1):
        res, rat = zip(*[W.check_trees(w, T[n], theta, wabs, extra) for n in orders])
        print("    %-30s |res| %s" % (label, " ".join("%8.1e" % float(r) for r in res)))
        print("    %-30s ratio %s" % ("", " ".join("%8.1e" % float(r) for r in rat)))
        return res, rat

    def exact_order(label, res, rat, p):
        ok = all(r <= 1 for r in rat[:p]) and rat[p] > 1e6
        check(ok, "%s: order exactly %d (orders ≤ %d hold to f64 rounding, max ratio %.2f; order %d fails, |res| %.1e)"
              % (label, p, p, float(max(rat[:p])), p + 1, float(res[p])))

    # ---- Tsit5
    A = [[exact_binary(x) for x in row] for row in ts["A"]]
    c = [exact_binary(x) for x in ts["C"]]
    b = [exact_binary(x) for x in ts["B"]]
    bt = [exact_binary(x) for x in ts["BTILDE"]]
    bhat = [x - y for x, y in zip(b, bt)]
    W = Weights(A)
    rs = max(abs(ci - mp.fsum(row)) / (2 * u * (abs(ci) + mp.fsum(abs(x) for x in row)) + TINY) for ci, row in zip(c, A))
    check(rs <= 1, "Tsit5 row sums c_i = Σ_j a_ij to f64 rounding (max ratio %.2f)" % float(rs))
    check(A[6][:6] == b[:6] and b[6] == 0, "Tsit5 FSAL: B equals row 7 of A, b₇ = 0")
    check(abs(mp.fsum(bt)) <= 2 * u * mp.fsum(abs(x) for x in bt), "Tsit5 Σ BTILDE = 0 (%s)" % mp.nstr(mp.fsum(bt), 3))
    print("    %-30s       %s" % ("order:", " ".join("%8d" % n for n in range(1, 7))))
    print("    %-30s       %s" % ("number of trees:", " ".join("%8d" % len(T[n]) for n in range(1, 7))))
    res, rat = table("b = B", W, b, range(1, 7))
    exact_order("Tsit5 B", res, rat, 5)
    DELTA["Tsit5"] = res[:5]
    res, rat = table("b̂ = B − BTILDE", W, bhat, range(1, 7), wabs=[abs(x) + abs(y) for x, y in zip(b, bt)])
    exact_order("Tsit5 B − BTILDE", res, rat, 4)
    R = [[exact_binary(x) for x in row] for row in ts["DENSE"]]
    for th in ("0.1", "0.25", "0.5", "0.75", "0.9", "1"):
        tth = mp.mpf(th)
        w = [tth * (r[0] + tth * (r[1] + tth * (r[2] + tth * r[3]))) for r in R]
        wabs = [tth * (abs(r[0]) + tth * (abs(r[1]) + tth * (abs(r[2]) + tth * abs(r[3])))) for r in R]
        res, rat = table("dense b(θ), θ = %s" % th, W, w, range(1, 7), tth, wabs, extra=2)
        exact_order("Tsit5 dense output at θ = %s" % th, res, rat, 5 if th == "1" else 4)
        DELTA["Tsit5 dense"] = [max(x, y) for x, y in zip(DELTA.get("Tsit5 dense", res[:4]), res[:4])]
    w1 = [mp.fsum(r) for r in R]
    ratio = max(abs(x - y) / (2 * u * (abs(y) + mp.fsum(abs(v) for v in r)) + TINY) for x, y, r in zip(w1, b, R))
    check(ratio <= 1, "Tsit5 b_i(1) = b_i (u(t₀+h) = y₁) to f64 rounding (max ratio %.2f)" % float(ratio))
    d1 = [r[0] + 2 * r[1] + 3 * r[2] + 4 * r[3] for r in R]
    ratio = max(abs(x - (1 if i == 6 else 0)) / (4 * u * mp.fsum(abs(v) for v in r) + 4 * u) for i, (x, r) in enumerate(zip(d1, R)))
    check(ratio <= 1 and R[0][0] == 1 and all(r[0] == 0 for r in R[1:]),
          "Tsit5 b'(0) = e₁ and b'(1) = e₇ (u' = f at both ends: C¹ across steps) (max ratio %.2f)" % float(ratio))
    # ---- DOP853
    A12 = [[exact_binary(x) for x in row] for row in dp["A"]]
    c12 = [exact_binary(x) for x in dp["C"]]
    b = [exact_binary(x) for x in dp["B"]]
    e5 = [exact_binary(x) for x in dp["E5"]]
    e3 = [exact_binary(x) for x in dp["E3"]]
    W = Weights(A12)
    A16 = [[exact_binary(x) for x in row] for row in dop853_extended(dp["A"], dp["B"], dp["C_EXTRA"], dp["A_EXTRA"])]
    c16 = c12 + [mp.mpf(1)] + [exact_binary(x) for x in dp["C_EXTRA"]]
    rs = max(abs(ci - mp.fsum(row)) / (2 * u * (abs(ci) + mp.fsum(abs(x) for x in row)) + TINY) for ci, row in zip(c16, A16))
    check(rs <= 1, "DOP853 row sums c_i = Σ_j a_ij, stages 1–12, 13 (= B, c = 1) and 14–16, to f64 rounding (max ratio %.2f)" % float(rs))
    for name, v in (("E5", e5), ("E3", e3)):
        check(abs(mp.fsum(v)) <= 2 * u * mp.fsum(abs(x) for x in v), "DOP853 Σ %s = 0 (%s)" % (name, mp.nstr(mp.fsum(v), 3)))
    print("    %-30s       %s" % ("order:", " ".join("%8d" % n for n in range(1, 10))))
    print("    %-30s       %s" % ("number of trees:", " ".join("%8d" % len(T[n]) for n in range(1, 10))))
    res, rat = table("b = B", W, b, range(1, 10))
    exact_order("DOP853 B", res, rat, 8)
    DELTA["DOP853"] = res[:8]
    for label, e, p in (("B − E5", e5, 5), ("B − E3 (bhh)", e3, 3)):
        res, rat = table(label, W, [x - y for x, y in zip(b, e)], range(1, p + 2), wabs=[abs(x) + abs(y) for x, y in zip(b, e)])
        exact_order("DOP853 " + label, res, rat, p)
    W16 = Weights(A16)
    D = [[exact_binary(x) for x in row] for row in dp["D"]]
    for th in ("0.1", "0.25", "0.5", "0.75", "0.9", "1"):
        w = dop853_dense_weights(b, D, th)
        wabs = dop853_dense_weights(b, D, th, absolute=True)
        res, rat = table("dense (CONTD8), θ = %s" % th, W16, w, range(1, 10 if th == "1" else 9), th, wabs, extra=2)
        exact_order("DOP853 dense output at θ = %s" % th, res, rat, 8 if th == "1" else 7)
        DELTA["DOP853 dense"] = [max(x, y) for x, y in zip(DELTA.get("DOP853 dense", res[:7]), res[:7])]


# ---------------------------------------------------------------------------------------------
# 3. Numerical convergence
# ---------------------------------------------------------------------------------------------
def integrate(method, prob, n):
    """Fixed step h = (t1 − t0)/n from the exact initial value: max error over the grid points
    and max error of the dense output at the step midpoints."""
    h = (prob.t1 - prob.t0) / n
    t, y = prob.t0, prob.exact(prob.t0)
    e_grid = e_mid = mp.mpf(0)
    for i in range(n):
        y1, ks, _ = method.step(prob.f, t, y, h)
        um = dense_eval(method, prob.f, t, y, h, ks, y1, "0.5")
        e_mid = max(e_mid, err(um, prob.exact(t + h / 2)))
        t, y = prob.t0 + (i + 1) * h, y1
        e_grid = max(e_grid, err(y, prob.exact(t)))
    return e_grid, e_mid


def observed(hs, es, floor):
    """Slope of the last pair of runs whose errors both stand above `floor(h)` (the level where
    the f64 rounding of the coefficients, not the truncation error, dominates)."""
    valid = [i for i in range(len(es) - 1) if es[i] > floor(hs[i]) and es[i + 1] > floor(hs[i + 1])]
    if not valid:
        return None
    i = valid[-1]
    return math.log(float(es[i] / es[i + 1])) / math.log(float(hs[i] / hs[i + 1]))


def report(label, hs, es, floor=None):
    sl = slopes(hs, es)
    marks = ["" if floor is None or (es[i] > floor(hs[i]) and es[i + 1] > floor(hs[i + 1])) else "*" for i in range(len(sl))]
    print("    %-34s %s" % (label, " ".join("%9.2e" % float(e) for e in es)))
    print("    %-34s      %s" % ("  slopes", " ".join("%9s" % ("%.2f%s" % (s, m)) for s, m in zip(sl, marks))))
    return observed(hs, es, floor) if floor else sl[-1]


def numerics(ts, dp):
    print("\n== 3. Fixed-step experiments (mpmath, 40 digits; coefficients = the f64 literals) ==")
    print("   slope = log(e_k/e_k+1)/log(h_k/h_k+1). The f64 coefficients leave order-condition")
    print("   residuals δ_k (section 2), an error floor F·h·Σ_k δ_k·h^(k-1) per step (F·T·Σ… globally,")
    print("   F = max|f| on the problem); '*' marks pairs with an error below 10× that floor. The")
    print("   last unmarked pair is the observed order. Local errors: one step from the exact")
    print("   solution, maximum over 8 starting points spread over [t0, t1].")
    mp.mp.dps = 40
    thetas = ["0.1", "0.3", "0.5", "0.7", "0.9"]
    summary = []
    for method, p, pd, est_orders in ((Tsit5(ts), 5, 4, {"btilde": 5}),
                                      (Dop853(dp), 8, 7, {"E5": 6, "E3": 4, "hairer": 8})):
        dl = DELTA[method.name]
        for prob in PROBLEMS:
            T = prob.t1 - prob.t0
            starts = [prob.t0 + T * (j + mp.mpf("0.5")) / 8 for j in range(8)]
            F = max(max(abs(x) for x in prob.f(t, prob.exact(t))) for t in starts + [prob.t0, prob.t1])
            base = lambda h, dl=dl: F * mp.fsum(d * h ** k for k, d in enumerate(dl))
            dld = DELTA[method.name + " dense"]
            base_dense = lambda h: F * mp.fsum(d * h ** k for k, d in enumerate(dld))
            print("\n  %s on %s, t in [%s, %s]" % (method.name, prob.name, mp.nstr(prob.t0, 3), mp.nstr(prob.t1, 5)))
            ns = prob.grid[method.name]
            hs = [T / n for n in ns]
            g, gm = zip(*[integrate(method, prob, n) for n in ns])
            print("    N = %s" % ns)
            gfloor = lambda h: 10 * T * base(h)
            o = report("global error (max over grid)", hs, g, gfloor)
            check(o is not None and abs(o - p) < 0.5, "%s, %s: global order %.2f (expect %d)" % (method.name, prob.name, o or 0, p))
            summary.append((method.name, prob.name, "global", p, o))
            report("dense error at midpoints (global)", hs, gm, lambda h: 10 * T * base(h) + 10 * h * base_dense(h))
            hl = [mp.mpf(prob.h0[method.name]) / 2 ** k for k in range(5)]
            rows = {}
            for h in hl:
                acc = {}
                for t0 in starts:
                    y0 = prob.exact(t0)
                    y1, ks, e = method.step(prob.f, t0, y0, h)
                    vals = {"local": err(y1, prob.exact(t0 + h)),
                            "dense θ=0.5": err(dense_eval(method, prob.f, t0, y0, h, ks, y1, "0.5"), prob.exact(t0 + h / 2)),
                            "dense max θ": max(err(dense_eval(method, prob.f, t0, y0, h, ks, y1, th), prob.exact(t0 + mp.mpf(th) * h)) for th in thetas)}
                    for k, v in e.items():
                        vals["estimator " + k] = max(abs(x) for x in v)
                    for k, v in vals.items():
                        acc[k] = max(acc.get(k, mp.mpf(0)), v)
                for k, v in acc.items():
                    rows.setdefault(k, []).append(v)
            print("    one step, h = %s·2^-k, k = 0..4" % prob.h0[method.name])
            lfloor = lambda h: 10 * h * base(h)
            dfloor = lambda h: 10 * h * base_dense(h)
            expect = {"local": p + 1, "dense θ=0.5": pd + 1, "dense max θ": pd + 1}
            expect.update({"estimator " + k: v for k, v in est_orders.items()})
            for k, v in rows.items():
                o = report("%s (expect h^%d)" % (k, expect[k]), hl, v, dfloor if k.startswith("dense") else lfloor)
                if prob.system or not k.startswith("estimator"):
                    check(o is not None and abs(o - expect[k]) < 0.5,
                          "%s, %s: %s ~ h^%.2f (expect h^%d)" % (method.name, prob.name, k, o or 0, expect[k]))
                    summary.append((method.name, prob.name, k, expect[k], o))
    return summary


def main():
    tableaux = os.path.join(HERE, "..", "runtime", "src", "integrators", "tableaux")
    ts = read_rust(os.path.join(tableaux, "tsit5.rs"))
    dp = read_rust(os.path.join(tableaux, "dop853.rs"))
    print("Read %d constants from tsit5_tableau.rs, %d from dop853_tableau.rs" % (len(ts), len(dp)))
    mp.mp.dps = 60
    fidelity(ts, dp)
    algebra(ts, dp)
    summary = numerics(ts, dp)
    print("\n== Summary of observed orders (last pair above the f64 floor) ==")
    print("    %-7s %-29s %-22s %8s %8s" % ("method", "problem", "quantity", "expected", "observed"))
    for m, prob, what, e, o in summary:
        print("    %-7s %-29s %-22s %8s %8.2f" % (m, prob, what, "h^%d" % e if what != "global" else "%d" % e, o or 0))
    print("\n%d check(s) failed" % len(FAILURES) if FAILURES else "\nALL CHECKS PASSED")
    for f in FAILURES:
        print("  FAILED: " + f)
    return 1 if FAILURES else 0


if __name__ == "__main__":
    sys.exit(main())
