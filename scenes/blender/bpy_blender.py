"""The `blender` command line, served by Blender as a Python module (`bpy`, the official builds on
PyPI; scripts/bpy-install.sh), for the scene tests written for a `blender` binary.

The official builds come to a test machine as the `bpy` wheel: a Python module, no `blender`
program. The scene scripts (scenes/blender/*.py) and the tests that start them
(tests/blender_scene_test.cpp) stay as they are: scripts/bpy-install.sh puts a `blender`
wrapper on a folder of its own that runs this file with the wheel's Python, and a test that
puts that folder first on PATH runs the official build. Only the command lines the tests use
are served:

  blender --version                                        "Blender 4.5.15 LTS" (first line)
  blender -b [--factory-startup] --python SCRIPT -- ARGS   SCRIPT as __main__, sys.argv as Blender's
  blender --command extension validate ZIP                 the extension validator Blender runs

A script that raises ends the run with exit status 1 (Blender's --python-exit-code 1); anything
else is a usage error (status 2) naming what it did not understand.
"""

import os
import runpy
import sys


def usage_error(argv, why):
    sys.stderr.write("bpy_blender: %s in: blender %s\n" % (why, " ".join(argv)))
    return 2


def main(argv):
    if argv[:1] == ["--version"]:
        import bpy
        print("Blender %s" % bpy.app.version_string)
        return 0
    if argv[:2] == ["--command", "extension"]:
        import bpy
        import addon_utils
        # The extension commands belong to the core add-on bl_pkg (Blender's `--command`
        # dispatches to it); the module imports it directly.
        addon_utils.enable("bl_pkg", default_set=True)
        import bl_pkg
        return bl_pkg.cli_extension(argv[2:])

    split = argv.index("--") if "--" in argv else len(argv)
    head, tail = argv[:split], argv[split + 1:]
    script = None
    i = 0
    while i < len(head):
        option = head[i]
        if option in ("-b", "--background", "--factory-startup"):
            # bpy is always in the background, and starts from the factory settings: the user
            # scripts and extensions live in the folders BLENDER_USER_* name, as for the binary.
            pass
        elif option == "--python" and i + 1 < len(head):
            script = head[i + 1]
            i += 1
        else:
            return usage_error(argv, "unknown option %r" % option)
        i += 1
    if script is None:
        return usage_error(argv, "no --python SCRIPT")

    import bpy  # loads Blender before the script, as the binary does
    # The binary's Python also sees the modules Blender bundles (bpy/<version>/python/…/site-packages:
    # oslquery, which Cycles' Script node compile imports, MaterialX); the module's does not.
    bundled = os.path.join(bpy.utils.resource_path("LOCAL"), "python", "lib",
                           "python%d.%d" % sys.version_info[:2], "site-packages")
    if os.path.isdir(bundled) and bundled not in sys.path:
        sys.path.append(bundled)
    sys.argv = [sys.argv[0]] + head + ["--"] + tail  # the script looks after "--", as in Blender
    try:
        runpy.run_path(script, run_name="__main__")
    except SystemExit as stop:
        return stop.code if isinstance(stop.code, int) else (0 if stop.code is None else 1)
    return 0


if __name__ == "__main__":
    try:
        status = main(sys.argv[1:])
    except Exception:  # a script's error: its traceback, and a failed run
        import traceback
        traceback.print_exc()
        status = 1
    sys.stdout.flush()
    sys.stderr.flush()
    # Blender's own exit skips the module's teardown, which can outlast a render; so does this.
    os._exit(status)
