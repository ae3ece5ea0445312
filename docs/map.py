"""Prints the map section of docs/ARCHITECTURE.md from the code: each folder's line, then
each file with the first sentence of its module doc (Rust `//!`, a Python docstring, a shell
header comment). Run from the repository root; paste the output between "### `src/`" and
"## Recipes". tests/integration/docs.rs checks that the map names every file."""

import subprocess, re, os, collections
files = [f for f in subprocess.run(['git','ls-files','--cached','--others','--exclude-standard'],capture_output=True,text=True).stdout.split('\n') if f]

def first_sentence(s):
    s=' '.join(s.split())
    cut=None
    for m in re.finditer(r'\.(\s+(?=[A-Z(`\[])|$)', s):
        before=s[:m.start()]
        if re.search(r'(\bal|e\.g|i\.e|etc|\.\.|\bvs)$', before):
            continue
        cut=m.start()+1; break
    s=s[:cut] if cut else s
    return re.sub(r'\[(`[^`]+`)\](\([^)]*\))?', r'\1', s)

def doc(path):
    text=open(path,encoding='utf-8').read()
    if path.endswith('.rs'):
        lines=[]
        for l in text.splitlines():
            if l.startswith('//!') or (path.startswith('fuzz/') and l.startswith('// ') and (not lines or not l.startswith('//!'))):
                lines.append(l[3:].strip())
            elif lines: break
        para=[]
        for l in lines:
            if not l: break
            para.append(l)
        return first_sentence(' '.join(para))
    if path.endswith(('.py','.pyi')):
        m=re.search(r'^(?:#[^\n]*\n)*\s*(?:"""|\'\'\')(.*?)(?:\n\s*\n|"""|\'\'\')', text, re.S)
        return first_sentence(m.group(1)) if m else ''
    if path.endswith('.js'):
        para=[]
        for l in text.splitlines():
            if l.startswith('// '):
                para.append(l[3:].strip())
            else: break
        return first_sentence(' '.join(para))
    if path.endswith('.sh') or path=='.ci/run':
        para=[]
        for l in text.splitlines()[1:]:
            if l.startswith('#'):
                para.append(l[1:].strip())
            else: break
        return first_sentence(' '.join(para))
    return ''

INTRO = {
 'src/': 'The library\'s root. `lib.rs` names the modules; each file beside it is one part that stands alone: the camera, checkpoints, the closed-set macro, explanations, jobs, the sampling lab.',
 'src/math/': 'The vocabulary every other part uses: rays, boxes, frames, transforms, offsets, random numbers, warps and their densities, and the statistics tests of sampling.',
 'src/sampler/': 'Where a sample\'s random numbers come from (the path tracer\'s `[integrator] sampler`).',
 'src/geometry/': 'Shapes in their own object space, one file each implementing `Intersect`, which the `Shape` enum forwards to (`closed_set!`); `Object` places one in the world.',
 'src/geometry/mesh/': 'Triangle meshes: their own wide BVH, and what a mesh carries per vertex.',
 'src/accel/': 'The scene\'s object BVH (binary, SAH) over `Object`s.',
 'src/accel/wide/': 'The eight-wide BVH a mesh walks, and its SIMD node test.',
 'src/bsdf/': 'BSDFs: pure functions of two directions in the shading frame, one file each implementing `Scatter`, which the `Bsdf` enum forwards to (`closed_set!`). Every BSDF passes harness.rs; those with a Mitsuba namesake pass mitsuba_tests.rs.',
 'src/material/': 'Materials as a scene file states them, textured, one file per `type`; each gives the BSDF at a point (path tracer) or the Phong terms (Whitted).',
 'src/texture/': 'Textures and what reads them: patterns (one file each implementing `Paint`, which the `Pattern` enum forwards to), images with their MIP maps and wraps, mappings from surface points to uv, and filtering over a pixel\'s footprint.',
 'src/light/': 'Every light behind one interface, `Emit`, in one list (`Light`, through `closed_set!`): point, spot, directional, area lights and the environment; and the choice of a light for next-event estimation.',
 'src/light/sky/': 'The daylight sky and its sun.',
 'src/denoise/': 'Denoising a finished picture: the albedo and normal images that guide a denoiser, made the way Intel Open Image Denoise asks, and its filter, behind the optional `denoise` feature (docs/denoise.md).',
 'src/mesh_file/': 'Mesh files read into plain mesh data (no scene types): OBJ with MTL, PLY, glTF.',
 'src/mesh_file/obj/': 'Wavefront OBJ: the parser, the mesh it builds at the end, MTL libraries and the text helpers both share.',
 'src/mesh_file/ply/': 'Stanford PLY: the header, the plan it gives, the two encodings, and the body read through them.',
 'src/mesh_file/gltf/': 'glTF 2.0 through the `gltf` crate, checked first so that no file makes it panic.',
 'src/scene/': 'The scene: its file format, its loading, and the immutable `Scene` every render thread shares, with the queries integrators make of it.',
 'src/scene/format/': 'The scene file one to one, as serde types; `snell schema` is generated from them (and constraints.rs).',
 'src/scene/load/': 'From a parsed file to a `Scene`: every value checked where it is written (each problem located, building going on to find the others), names and paths resolved, files read.',
 'src/scene/gltf/': 'A glTF file as a scene places it: its meshes, materials, cameras and lights as snell\'s.',
 'src/scene/detail/': 'Normal and bump maps applied at a hit.',
 'src/integrator/': 'Ways of turning a camera ray into a colour, or a light\'s path into splats: Whitted, the path tracer, the light tracer, bidirectional path tracing, the debug views, and the recorders behind `snell explain`.',
 'src/integrator/whitted/': 'Whitted-style ray tracing (the default integrator): the recursion of reflected and refracted rays with Phong direct light, and its shadow rays through transparent objects.',
 'src/integrator/bdpt/': 'Bidirectional path tracing (`[integrator] type = "bdpt"`): the two subpaths, their vertices with the densities both ways, the joins, and the MIS weight of each strategy.',
 'src/render/bdpt/': 'The bidirectionally path-traced render: camera samples to the film and light paths joined to the eye as splats, in passes; its tests against the path tracer and the caustic\'s energy.',
 'src/lpe/': 'Light path expressions: which of a pixel\'s light came by which kind of path (`--lpe`, `[[image.lpe]]`, docs/lpe.md), from the text of an expression to the table a render steps through.',
 'src/render/light/': 'The tests of the light-traced render (src/render/light.rs) against the path tracer.',
 'src/render/lpe/': 'The tests of the render with light path expressions (src/render/lpe.rs).',
 'src/film/': 'Where samples land: the reconstruction filter, the film of per-pixel sums, tiles and regions.',
 'src/render/': 'The render loop every render takes (whole, in passes, progressive, debug views), and the estimate of its time.',
 'src/output/': 'Writing what a render makes, never leaving a broken file and never over a file the render reads.',
 'src/bin/snell/': 'The command line, a front end: it parses flags (clap), calls the library, prints, and maps errors to exit codes.',
 'src/bin/snell/render/': '`snell render`, split by what it does beside rendering.',
 'src/bin/snell/serve/': '`snell serve`, the live preview. Its dependencies (axum, tokio, notify) are a front end\'s, so it lives in the binary.',
 'src/bin/snell/serve/page/': 'The page itself, built into the binary with `include_str!`.',
 'tests/integration/': 'One test binary (`main.rs` names the modules) of tests through the public API and the built `snell` binary. Unit tests live beside their code in `src/`.',
 'tests/integration/cli/': 'The command line as a user meets it, through the built binary.',
 'tests/integration/schema/': 'The JSON Schema against the parser and against `snell check`.',
 'tests/integration/serve/': '`snell serve` tested over real sockets and, in browser.rs, in a real browser.',
 'benches/': '`cargo bench` (criterion).',
 'examples/': 'Programs that use the library for a benchmark; `snell-tour.ipynb`, the Python module\'s tour notebook (CI runs it: snell-py/tests/test_notebook.py).',
 'bench/': 'Benchmarks against the peers and between builds, each printing its figures; their results go to docs/perf-log.md.',
 'fuzz/fuzz_targets/': 'cargo-fuzz targets, one per kind of input a user hands snell (docs/fuzzing.md); `fuzz/seeds/` holds their starting corpora.',
 'python/snell_farm/': 'snell-farm, the Ray farm driver (`pip install ./python`), which calls the `snell` binary (docs/farm.md).',
 'python/tests/': 'snell-farm\'s tests (pytest), run by `.ci/run`.',
 'snell-py/src/': 'The Python module\'s native half, `snell._snell` (pyo3 and rust-numpy; a crate of the workspace, so that snell keeps `forbid(unsafe_code)`): what needs Rust, with the interpreter\'s lock released where it works.',
 'snell-py/python/snell/': 'The Python package `snell` (`pip install ./snell-py`, built by maturin): the shape a script sees, around `_snell`.',
 'snell-py/tests/': 'The Python module\'s tests (pytest), against the `snell` binary `cargo test` built; run by `.ci/run`.',
}
# The page's markup and style, which have no header comment of their own (each script's
# line is its header's first sentence).
PAGE = {
 'index.html': 'The page\'s markup: the picture, the controls (exposure, tone curve, integrator), the status line and the explain panel.',
 'style.css': 'The page\'s look (and the lab page\'s).',
 'lab.html': 'The sampling lab\'s page (`/lab`, linked from the preview): a material\'s form, the test\'s answer, and three canvases for the histograms.',
}
ORDER = ['src/','src/math/','src/sampler/','src/geometry/','src/geometry/mesh/','src/accel/','src/accel/wide/',
 'src/bsdf/','src/material/','src/texture/','src/light/','src/light/sky/','src/mesh_file/','src/mesh_file/obj/','src/mesh_file/ply/','src/mesh_file/gltf/',
 'src/scene/','src/scene/format/','src/scene/load/','src/scene/gltf/','src/scene/detail/','src/integrator/','src/integrator/whitted/','src/integrator/bdpt/','src/lpe/',
 'src/film/','src/render/','src/render/bdpt/','src/render/light/','src/render/lpe/','src/denoise/','src/output/','src/bin/snell/','src/bin/snell/render/','src/bin/snell/serve/','src/bin/snell/serve/page/',
 'tests/integration/','tests/integration/cli/','tests/integration/schema/','tests/integration/serve/','benches/','examples/','bench/','fuzz/fuzz_targets/','python/snell_farm/','python/tests/','snell-py/src/','snell-py/python/snell/','snell-py/tests/']
groups=collections.OrderedDict((d,[]) for d in ORDER)
for f in files:
    if f.startswith(('tests/bad/','tests/data/','tests/golden/','fuzz/seeds','docs/','assets/','scenes/','"')): continue
    if f == 'snell-py/build.rs': continue  # the package's root, described by hand as the root's is
    if not os.path.exists(f): continue
    d=os.path.dirname(f)+'/'
    if d not in groups:
        if f.endswith(('.rs','.py','.sh')) and d.startswith(('src/','tests/integration/','bench/','python/snell_farm/','python/tests/','snell-py/')) and not d.startswith('python/tests/data'):
            raise SystemExit(f'{d}: a folder this script does not know; add it to ORDER and INTRO')
        continue
    b=os.path.basename(f)
    if d=='src/bin/snell/serve/page/':
        # A script's own header where it has one; the markup and style from PAGE.
        groups[d].append((b,doc(f) or PAGE[b])); continue
    if not f.endswith(('.rs','.py','.pyi','.sh')): continue
    groups[d].append((b,doc(f)))
out=[]
for d,items in groups.items():
    out.append(f'\n### `{d}`\n')
    out.append(INTRO[d]+'\n')
    for n,s in items:
        assert s, (d,n)
        out.append(f'- `{n}`: {s}')
print('\n'.join(out))
