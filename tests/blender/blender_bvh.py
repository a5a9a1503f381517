# Drives Blender (Debian's blender 3.4, headless) as a user's other tool: imports a BVH file and
# exports it again as Blender writes BVH (its own axes, Z up, position channels on every joint).
#   blender -b --factory-startup --python blender_bvh.py -- IN.bvh OUT.bvh
# Prints "blender: bones B frames F fps R" for what it read. Exits 1 on any error.
import builtins
import sys

# Blender 3.4's importer opens files with mode 'rU', which Python 3.11 rejects: drop the 'U'.
_open = builtins.open


def _open_without_u(file, mode='r', *args, **kwargs):
    return _open(file, mode.replace('U', ''), *args, **kwargs)


builtins.open = _open_without_u

import bpy  # noqa: E402 (after the patch)


def frames_in(path):
    with _open(path) as f:
        for line in f:
            if line.strip().startswith('Frames:'):
                return int(line.split()[1])
    raise RuntimeError(path + ': no Frames: line')


try:
    source, target = sys.argv[sys.argv.index('--') + 1:][:2]
    bpy.ops.wm.read_factory_settings(use_empty=True)
    bpy.ops.import_anim.bvh(filepath=source, update_scene_fps=True, update_scene_duration=True)
    armature = next(o for o in bpy.data.objects if o.type == 'ARMATURE')
    scene = bpy.context.scene
    frames = frames_in(source)
    # The importer's scene range ends one frame past the file's last (1..N+1): export the file's N.
    first = scene.frame_start
    print('blender: bones %d frames %d fps %g' % (len(armature.data.bones), frames,
                                                   scene.render.fps / scene.render.fps_base))
    bpy.ops.export_anim.bvh(filepath=target, frame_start=first, frame_end=first + frames - 1)
except Exception as error:  # a failed import or export must fail the test, not pass silently
    print('blender: ' + repr(error))
    sys.exit(1)
