"""``bouncer scenes``: list the built-in scenes."""

from reports.runs.scenes import builtin_scenes, parse_scene


def _scenes(args):
    for name, text in builtin_scenes().items():
        scene = parse_scene(text, name)
        curves = sum(len(x.curves) for x in scene.experiments())
        print(f"{name:20s} {scene.kind:12s} eps={scene.eps:g}  {scene.particles} particles x "
              f"{len(scene.experiments())} start sets, {curves} curves  {scene.description}")
    return 0


def add_parser(subparsers):
    scenes = subparsers.add_parser("scenes", help="list the built-in scenes")
    scenes.set_defaults(func=_scenes)
