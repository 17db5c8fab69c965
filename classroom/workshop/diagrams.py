#!/usr/bin/env python3
# The lecture notes' path diagrams (lecture_notes/figures/path-*.svg), drawn as the slides label
# paths: x_0 on the light .. x_k at the pinhole, s vertices from the light (orange), t from the
# camera (blue), k = s + t - 1 segments. Plain SVG, no dependency: python3 classroom/workshop/diagrams.py
# rewrites them (the committed files are its output).
import os

OUT = os.path.join(os.path.dirname(__file__), "..", "..", "lecture_notes", "figures")
LIGHT, CAMERA, GREY, INK = "#d55e00", "#0072b2", "#999999", "#000000"


class Svg:
    def __init__(self, width, height, title):
        self.w, self.h, self.items = width, height, []
        self.title = title

    def line(self, a, b, colour=INK, width=2.5, dash=None, arrow=False):
        d = f' stroke-dasharray="{dash}"' if dash else ""
        m = f' marker-end="url(#m{colour[1:]})"' if arrow else ""
        self.items.append(f'<line x1="{a[0]}" y1="{a[1]}" x2="{b[0]}" y2="{b[1]}" stroke="{colour}" stroke-width="{width}"{d}{m}/>')

    def dot(self, p, colour=INK, r=7):
        self.items.append(f'<circle cx="{p[0]}" cy="{p[1]}" r="{r}" fill="{colour}"/>')

    def ring(self, p, r, colour, fill="none", dash=None):
        d = f' stroke-dasharray="{dash}"' if dash else ""
        self.items.append(f'<circle cx="{p[0]}" cy="{p[1]}" r="{r}" fill="{fill}" stroke="{colour}" stroke-width="2"{d}/>')

    def text(self, p, s, colour=INK, anchor="middle", size=16, italic=False):
        style = ' font-style="italic"' if italic else ""
        s = s.replace("&", "&amp;").replace("<", "&lt;").replace(">", "&gt;")
        self.items.append(f'<text x="{p[0]}" y="{p[1]}" fill="{colour}" text-anchor="{anchor}" font-size="{size}"{style}>{s}</text>')

    def lamp(self, p):  # a lamp: a thick bar above its point
        self.items.append(f'<rect x="{p[0] - 28}" y="{p[1] - 14}" width="56" height="7" fill="#e6b800" stroke="{INK}"/>')

    def pinhole(self, p):  # a camera: a small box opening toward the scene (to the left)
        x, y = p
        self.items.append(f'<path d="M{x},{y} L{x + 26},{y - 14} L{x + 26},{y + 14} z" fill="#dddddd" stroke="{INK}" stroke-width="1.5"/>')

    def wall(self, a, b):
        self.items.append(f'<line x1="{a[0]}" y1="{a[1]}" x2="{b[0]}" y2="{b[1]}" stroke="#555555" stroke-width="5"/>')

    def save(self, name):
        colours = {LIGHT, CAMERA, GREY, INK}
        markers = "".join(f'<marker id="m{c[1:]}" viewBox="0 0 10 10" refX="9" refY="5" markerWidth="6" markerHeight="6" '
                          f'orient="auto"><path d="M0,0 L10,5 L0,10 z" fill="{c}"/></marker>' for c in sorted(colours))
        body = "\n".join(self.items)
        svg = (f'<svg xmlns="http://www.w3.org/2000/svg" width="{self.w}" height="{self.h}" viewBox="0 0 {self.w} {self.h}" '
               f'font-family="DejaVu Sans, sans-serif">\n<title>{self.title}</title>\n<rect width="{self.w}" height="{self.h}" fill="white"/>\n'
               f'<defs>{markers}</defs>\n{body}\n</svg>\n')
        with open(os.path.join(OUT, name), "w") as f:
            f.write(svg)


def towards(a, b, shorten=10):  # the segment a -> b, stopped short of b's dot (for an arrowhead)
    dx, dy = b[0] - a[0], b[1] - a[1]
    n = (dx * dx + dy * dy) ** 0.5
    return (round(b[0] - dx / n * shorten, 1), round(b[1] - dy / n * shorten, 1))


def path(svg, pts, s, label_below, names=None, connect=True):
    """A path x_0..x_k through pts (x_0 first, on the lamp; x_k the pinhole), strategy s: x_0..x_{s-1}
    sampled from the light, x_s..x_k from the camera, the connection x_{s-1} - x_s dashed."""
    k = len(pts) - 1
    svg.lamp(pts[0])
    svg.pinhole(pts[k])
    for i in range(k):
        a, b = pts[i], pts[i + 1]
        if i < s - 1:
            svg.line(a, towards(a, b), LIGHT, arrow=True)  # the light subpath sampled x_{i+1} from x_i
        elif i == s - 1 and connect:
            svg.line(a, b, INK, 2, dash="7,5")  # the connection: a shadow ray, nothing sampled
        elif i >= s:
            svg.line(b, towards(b, a), CAMERA, arrow=True)  # the camera subpath sampled x_i from x_{i+1}
    for i, p in enumerate(pts):
        svg.dot(p, LIGHT if i < s else CAMERA)
        name = names[i] if names else f"x{i}"
        below = label_below[i]
        svg.text((p[0], p[1] + (30 if below else -22)), name, LIGHT if i < s else CAMERA)


def bdpt():  # page 3: one strategy's path
    svg = Svg(760, 300, "A bdpt path: strategy (s,t) = (2,3)")
    pts = [(80, 80), (230, 210), (400, 90), (560, 220), (660, 150)]
    path(svg, pts, 2, [True, True, False, True, True],
         ["x0 = y0 (lamp)", "x1 = y1", "x2 = z2", "x3 = z1", "x4 = z0 (pinhole)"])
    svg.text((315, 175), "connection", INK, size=15, italic=True)
    svg.text((315, 193), "(a shadow ray)", INK, size=15, italic=True)
    svg.text((20, 285), "light subpath y0 y1: s = 2 vertices", LIGHT, anchor="start")
    svg.text((400, 285), "camera subpath z0 z1 z2: t = 3", CAMERA, anchor="start")
    svg.text((380, 30), "strategy (s,t) = (2,3): k = s + t - 1 = 4 segments", INK, size=17)
    svg.save("path-bdpt.svg")


def densities():  # page 7: one vertex changes sides between two strategies
    svg = Svg(760, 520, "p_{k,s+1} / p_{k,s} = pdfRev(x_s) / pdfFwd(x_s)")
    for row, s in enumerate((2, 3)):
        y0 = 30 + row * 235
        pts = [(80, y0 + 60), (230, y0 + 170), (400, y0 + 70), (560, y0 + 180), (680, y0 + 120)]
        path(svg, pts, s, [True, True, False, True, True])
        svg.text((20, y0 + 5), f"strategy s = {s}, t = {5 - s}: p_(4,{s})", INK, anchor="start", size=17)
        x2 = pts[2]
        svg.ring(x2, 16, LIGHT if s == 3 else CAMERA)
        who = "pdfFwd(x2): the camera subpath sampled x2" if s == 2 else "pdfRev(x2): now the light subpath samples x2"
        svg.text((x2[0] + 26, x2[1] - 4), who, LIGHT if s == 3 else CAMERA, anchor="start", size=15)
    svg.text((380, 505), "p_(4,3) / p_(4,2) = pdfRev(x2) / pdfFwd(x2): only x2 changed sides", INK, size=17)
    svg.save("path-densities.svg")


def formulation():  # page 8: the throughput's factors along a path, in the slides' p numbering
    svg = Svg(760, 330, "T(pi) along a path of three segments")
    pts = [(680, 170), (520, 260), (330, 110), (110, 230)]  # p0 the eye .. p3 on the light
    svg.pinhole(pts[0])
    svg.lamp(pts[3])
    for i in range(3):
        svg.line(pts[i], pts[i + 1], GREY, 2.5)
        mid = ((pts[i][0] + pts[i + 1][0]) / 2, (pts[i][1] + pts[i + 1][1]) / 2)
        svg.text((mid[0] + (40 if i == 1 else 0), mid[1] + (28 if i != 1 else -10)), f"G(p{i + 1} <-> p{i})", INK, size=15)
    for i, p in enumerate(pts):
        svg.dot(p)
    svg.text((680, 145), "p0 (eye)")
    svg.text((520, 290), "p1")
    svg.text((330, 90), "p2")
    svg.text((110, 262), "p3 (light)")
    svg.text((520, 314), "f(p2 -> p1 -> p0)", INK, size=15, italic=True)
    svg.text((330, 66), "f(p3 -> p2 -> p1)", INK, size=15, italic=True)
    svg.text((110, 286), "Le(p3 -> p2)", INK, size=15, italic=True)
    svg.text((380, 28), "L(pi) = Le(p3 -> p2) G f(p3 -> p2 -> p1) G f(p2 -> p1 -> p0) G W", INK, size=16)
    svg.save("path-formulation.svg")


def strategies():  # page 10: one path, every strategy that makes it
    svg = Svg(880, 330, "The four strategies that make a path of three segments")
    base = [(40, 60), (100, 150), (150, 70), (190, 130)]
    for s in range(4):
        ox = 15 + s * 215
        pts = [(x + ox - 20, y + 40) for x, y in base]
        path(svg, pts, s, [True, True, False, True], connect=s > 0)
        what = ["s = 0: it hits the lamp", "s = 1: next event", "s = 2: a connection",
                "s = 3: light tracing (t = 1)"][s]
        svg.text((ox + 90, 275), what, INK, size=13)
        svg.text((ox + 90, 300), f"p_(3,{s})", INK, size=16)
    svg.text((430, 26), "one path x0 x1 x2 x3, four ways to sample it: MIS weighs them", INK, size=17)
    svg.save("path-strategies.svg")


def merge():  # page 15: a merge, and a disk that straddles a wall
    svg = Svg(860, 330, "Vertex merging: a light vertex within r of a camera vertex")
    lamp, y1, y = (60, 70), (210, 220), (380, 150)
    x, eye = (400, 160), (560, 80)
    svg.lamp(lamp)
    svg.pinhole(eye)
    svg.line(lamp, towards(lamp, y1), LIGHT, arrow=True)
    svg.line(y1, towards(y1, y), LIGHT, arrow=True)
    svg.line(eye, towards(eye, x), CAMERA, arrow=True)
    svg.ring(x, 45, INK, fill="#f2f2f2", dash="5,4")
    svg.dot(lamp, LIGHT)
    svg.dot(y1, LIGHT)
    svg.dot(y, LIGHT)
    svg.dot(x, CAMERA)
    svg.text((60, 105), "y0", LIGHT)
    svg.text((210, 250), "y1", LIGHT)
    svg.text((350, 140), "y", LIGHT)
    svg.text((425, 190), "x", CAMERA)
    svg.line((400, 160), (443, 160), INK, 1.5)
    svg.text((430, 152), "r", INK, size=15, italic=True)
    svg.text((560, 120), "z0", CAMERA)
    svg.text((300, 295), "the merge counts y's light at x: p = p_(k,s) pi r^2 N p_light(x)", INK, size=15)
    # The inset: a wall without thickness between a dark room and a lit one.
    svg.wall((720, 60), (720, 260))
    svg.ring((705, 170), 45, INK, fill="#f2f2f2", dash="5,4")
    svg.dot((705, 170), CAMERA)
    for p in ((735, 150), (740, 190), (730, 205)):
        svg.dot(p, LIGHT, 5)
    svg.text((660, 50), "dark room", INK, size=14)
    svg.text((790, 50), "lit room", INK, size=14)
    svg.text((720, 295), "a disk across a thin wall: light leaks", INK, size=14)
    svg.save("path-merge.svg")


def mutation():  # page 16: a small step and a large step in primary sample space, and their paths
    svg = Svg(860, 330, "Metropolis in primary sample space: a small step and a large step")
    ox, oy, side = 40, 50, 230
    svg.items.append(f'<rect x="{ox}" y="{oy}" width="{side}" height="{side}" fill="none" stroke="{INK}" stroke-width="2"/>')
    u, small, large = (120, 170), (138, 152), (230, 80)
    svg.ring(u, 24, GREY, dash="4,3")
    svg.dot(u, INK)
    svg.dot(small, CAMERA)
    svg.dot(large, LIGHT)
    svg.line(u, towards(u, small), CAMERA, 2, arrow=True)
    svg.line(u, towards(u, large), LIGHT, 2, dash="6,4", arrow=True)
    svg.text((u[0] - 10, u[1] + 40), "u", INK)
    svg.text((small[0] + 24, small[1] + 6), "v", CAMERA)
    svg.text((large[0] - 6, large[1] - 14), "v'", LIGHT)
    svg.text((ox + side / 2, oy + side + 30), "the numbers u in [0,1)^n", INK, size=15)
    svg.text((ox + side / 2, 30), "small step: v near u; large: v' anywhere", INK, size=14)
    # The paths the three states make (the same lamp and camera).
    lamp, eye = (360, 230), (800, 120)
    svg.lamp(lamp)
    svg.pinhole(eye)
    for pts, colour, dash in (([lamp, (480, 90), (640, 200), eye], INK, None),
                              ([lamp, (495, 80), (655, 190), eye], CAMERA, "6,4"),
                              ([lamp, (560, 270), (700, 60), eye], LIGHT, "6,4")):
        for a, b in zip(pts, pts[1:]):
            svg.line(a, b, colour, 2, dash=dash)
        for p in pts[1:-1]:
            svg.dot(p, colour, 5)
    svg.text((470, 70), "path(u)", INK, size=14)
    svg.text((700, 215), "path(v)", CAMERA, size=14)
    svg.text((560, 300), "path(v') elsewhere", LIGHT, size=14)
    svg.text((580, 24), "accept v with a = min(1, f(v) / f(u)); splat both, by a and 1 - a", INK, size=15)
    svg.save("path-mutation.svg")


def mirror():  # page 10M: a mirror unfolded, and one interface
    svg = Svg(860, 360, "Through a mirror and through one interface")
    # Left: a -> m on the mirror -> b, and b's mirror image b' on the straight line from a.
    svg.wall((60, 230), (400, 230))
    a, m, b, bb = (90, 100), (248, 230), (370, 130), (370, 330)  # m on the line a - b'
    svg.line(a, towards(a, m), LIGHT, arrow=True)
    svg.line(m, towards(m, b), LIGHT, arrow=True)
    svg.line(m, bb, GREY, 2, dash="6,5")
    svg.dot(a, LIGHT)
    svg.dot(m, INK, 5)
    svg.dot(b, LIGHT)
    svg.ring(bb, 7, GREY, dash="3,2")
    svg.text((90, 85), "a", LIGHT)
    svg.text((150, 250), "mirror", INK, size=15)
    svg.text((150, 160), "d1", LIGHT, size=14)
    svg.text((325, 200), "d2", LIGHT, size=14)
    # b on a surface of its own, facing the mirror: cos_b is the cosine at b, to its normal.
    svg.wall((340, 130), (400, 130))
    svg.line(b, (370, 172), GREY, 2, dash="4,3")
    svg.text((378, 170), "n_b", GREY, anchor="start", size=13)
    svg.text((358, 172), "cos_b", LIGHT, anchor="end", size=13)
    svg.text((388, 118), "b", LIGHT, anchor="start")
    svg.text((355, 340), "b' (b unfolded)", GREY, anchor="end", size=15)
    svg.text((230, 28), "a mirror: b lies where the straight line reaches b'", INK, size=16)
    svg.text((230, 50), "density at b: p_omega(a) |cos_b| / (d1 + d2)^2", INK, size=15)
    # Right: one interface, air above, water below.
    svg.items.append('<rect x="470" y="200" width="360" height="130" fill="#dcebf7"/>')
    svg.wall((470, 200), (830, 200))
    a2, x, b2 = (540, 100), (650, 200), (720, 300)
    svg.line(a2, towards(a2, x), LIGHT, arrow=True)
    svg.line(x, towards(x, b2), LIGHT, arrow=True)
    svg.dot(a2, LIGHT)
    svg.dot(x, INK, 5)
    svg.dot(b2, LIGHT)
    svg.text((555, 95), "a (air, eta_a = 1)", LIGHT, anchor="start")
    svg.text((705, 325), "b (water, eta_b = 1.33)", LIGHT, anchor="end", size=14)
    svg.text((790, 190), "surface", INK, size=14)
    svg.text((650, 28), "one interface keeps eta^2 |cos| d omega:", INK, size=16)
    svg.text((650, 50), "the ends differ by eta_b^2 / eta_a^2 = 1.77", INK, size=15)
    svg.save("path-mirror.svg")


def pinhole():  # page 5: the film at distance 1, dA = d omega / cos^3, W_e = 1/(A cos^4)
    svg = Svg(860, 380, "The pinhole's film at distance 1")
    eye, axis_end = (90, 250), (520, 250)
    svg.line(eye, axis_end, GREY, 2, dash="6,5")
    svg.items.append('<line x1="390" y1="70" x2="390" y2="330" stroke="#555555" stroke-width="4"/>')  # the film, distance 1
    scene = (800, 22)  # the ray at theta: it meets the film 1/cos theta away, at y = 154
    svg.line(eye, towards(eye, scene, 4), CAMERA, arrow=True)
    svg.pinhole((eye[0] - 26, eye[1]))
    svg.dot(eye, INK, 5)
    svg.items.append('<rect x="385" y="142" width="10" height="24" fill="#e6b800" stroke="#000000"/>')  # dA on the film
    svg.items.append('<path d="M150,250 A60,60 0 0,0 145,225" fill="none" stroke="#000000" stroke-width="1.5"/>')
    svg.text((170, 236), "theta", INK, anchor="start", size=15)
    svg.text((240, 272), "1 (the film's distance)", GREY, size=14)
    svg.text((236, 172), "1 / cos theta", CAMERA, size=15)
    svg.text((402, 190), "dA (a film patch)", INK, anchor="start", size=15)
    svg.text((390, 352), "film, area A (the image rectangle)", INK, size=15)
    svg.text((60, 300), "pinhole", INK, anchor="start", size=15)
    svg.text((430, 30), "dA, seen from the pinhole 1/cos theta away and tilted by theta:", INK, size=16)
    svg.text((430, 52), "d omega = dA cos theta / (1/cos theta)^2 = dA cos^3 theta", INK, size=15)
    svg.text((600, 230), "a uniform film point, p_A = 1/A:", INK, anchor="start", size=15)
    svg.text((600, 252), "p_omega = 1 / (A cos^3 theta)", INK, anchor="start", size=15)
    svg.text((600, 286), "W_e = 1 / (A cos^4 theta):", INK, anchor="start", size=15)
    svg.text((600, 308), "W_e cos theta / p_omega = 1", INK, anchor="start", size=15)
    svg.save("path-pinhole.svg")


def shading():  # page 13: n_g, n_s, a grazing direction, the slide's apparent areas
    svg = Svg(900, 380, "A shading normal and a grazing direction")
    svg.wall((60, 280), (560, 280))
    x = (300, 280)
    svg.line(x, (300, 90), INK, 2.5, arrow=True)  # n_g
    svg.line(x, (400, 110), LIGHT, 2.5, arrow=True)  # n_s, tilted toward the light
    svg.text((292, 84), "n_g (the surface's)", INK, anchor="end", size=15)
    svg.text((408, 106), "n_s (the shading normal)", LIGHT, anchor="start", size=15)
    light = (680, 240)  # the light arrives at grazing incidence: |w . n_g| = 0.10, |w . n_s| = 0.60
    svg.line(light, towards(light, x, 8), CAMERA, arrow=True)
    svg.text((690, 246), "w (grazing)", CAMERA, anchor="start", size=15)
    svg.items.append('<rect x="260" y="276" width="80" height="8" fill="#e6b800" stroke="#000000"/>')  # dA
    svg.text((300, 310), "dA", INK, size=15)
    # What w sees of dA, as bars in proportion: dA |w . n_g| (the geometry), dA |w . n_s| (as n_s has it).
    svg.line((600, 340), (600, 330), INK, 6)
    svg.text((612, 342), "dA |w . n_g|: apparently small", INK, anchor="start", size=14)
    svg.line((600, 200), (600, 140), LIGHT, 6)
    svg.text((612, 176), "dA |w . n_s|: apparently much larger", LIGHT, anchor="start", size=14)
    svg.text((450, 30), "Light arrives over the small area the geometry shows and leaves as from the", INK, size=15)
    svg.text((450, 52), "larger one n_s shows: the factor |w . n_s| / |w . n_g| has no bound", INK, size=15)
    svg.save("path-shading-normal.svg")

if __name__ == "__main__":
    for draw in (bdpt, densities, formulation, strategies, merge, mutation, mirror, pinhole, shading):
        draw()
    print("wrote lecture_notes/figures/path-{bdpt,densities,formulation,strategies,merge,mutation,mirror,pinhole,shading-normal}.svg")
