"""Writing files: Still.write() and write_image() follow the command line's output rules. A picture is written
beside its place and renamed over it, so the place must be a regular file or a new name (a FIFO, a device or a link
to one is refused, never replaced), and a still is never written over a file its render read."""

from __future__ import annotations

import os
import shutil
import stat
import subprocess

import numpy as np
import pytest

import inkgraph
from conftest import SIZE
from pngread import read_png

REPLACE_TAIL = ("; outputs are written as new files and renamed into place, which would replace it, so give the name "
                "of a regular file or a new one")


@pytest.fixture(scope="module")
def still(suzanne) -> inkgraph.Still:
    return inkgraph.render(suzanne, size=SIZE).still


def writers(still):
    """Every way Python writes a picture: the still's own and write_image()."""
    return {"Still.write": still.write, "write_image": lambda path: inkgraph.write_image(path, still.picture)}


def command_line_output_error(executable, model, output, folder, *flags) -> tuple[str, int]:
    """What `inkgraph render MODEL -o OUTPUT FLAGS...` says, without "inkgraph: ", and its exit code."""
    run = subprocess.run([str(executable), "render", str(model), "-o", str(output), "--size", "16x16", *flags],
                         cwd=folder, capture_output=True, text=True)
    return run.stderr.splitlines()[0].removeprefix("inkgraph: "), run.returncode


def refused_output(write, path) -> inkgraph.OutputError:
    with pytest.raises(inkgraph.OutputError) as caught:
        write(os.fspath(path))
    assert caught.value.exit_code == 5 and caught.value.kind == "output"
    return caught.value


@pytest.mark.parametrize("writer", ["Still.write", "write_image"])
def test_a_fifo_named_png_is_refused_not_replaced(still, writer, tmp_path, suzanne_path, inkgraph_executable):
    fifo = tmp_path / "x.png"
    os.mkfifo(fifo)
    error = refused_output(writers(still)[writer], fifo)
    assert str(error) == f"writeImage(): '{fifo}' is a FIFO" + REPLACE_TAIL
    assert stat.S_ISFIFO(os.lstat(fifo).st_mode)
    assert os.listdir(tmp_path) == ["x.png"]  # no temporary left beside it
    # The command line refuses it in the same words and with the same exit code.
    message, code = command_line_output_error(inkgraph_executable, suzanne_path, fifo, tmp_path)
    assert (message, code) == (f"checkOutputs(): -o '{fifo}' is a FIFO" + REPLACE_TAIL, error.exit_code)


@pytest.mark.parametrize("writer", ["Still.write", "write_image"])
def test_a_link_to_dev_null_named_png_is_refused(still, writer, tmp_path):
    link = tmp_path / "x.png"
    link.symlink_to("/dev/null")
    error = refused_output(writers(still)[writer], link)
    assert str(error) == f"writeImage(): '{link}' is a character device" + REPLACE_TAIL
    assert os.path.islink(link) and os.readlink(link) == "/dev/null"
    assert stat.S_ISCHR(os.stat("/dev/null").st_mode)


@pytest.mark.skipif(os.geteuid() != 0, reason="mknod of a character device needs root")
@pytest.mark.parametrize("writer", ["Still.write", "write_image"])
def test_a_character_device_named_png_is_refused_not_replaced(still, writer, tmp_path):
    device = tmp_path / "x.png"
    os.mknod(device, stat.S_IFCHR | 0o666, os.makedev(1, 3))  # what /dev/null is
    error = refused_output(writers(still)[writer], device)
    assert str(error) == f"writeImage(): '{device}' is a character device" + REPLACE_TAIL
    assert stat.S_ISCHR(os.lstat(device).st_mode)


def test_a_still_is_never_written_over_a_file_its_render_read(repo, tmp_path, suzanne_path, inkgraph_executable):
    model = tmp_path / "model.obj"
    shade_map = tmp_path / "map.png"
    shutil.copyfile(suzanne_path, model)
    shutil.copyfile(repo / "shademaps" / "duotone-cool.png", shade_map)
    originals = {path: path.read_bytes() for path in (model, shade_map)}
    result = inkgraph.render(model, look={"shading": "comic", "shademap": str(shade_map)}, size=SIZE)
    for path, what in ((model, "the model itself"), (shade_map, "the look's shade map")):
        with pytest.raises(inkgraph.UsageError) as caught:
            result.write(path)
        error = caught.value
        assert str(error) == f"Still::write(): '{path}' is {what}; choose another file"
        assert error.exit_code == 2 and error.kind == "usage"
    assert {path: path.read_bytes() for path in originals} == originals
    # The command line's -o says the same of the shade map, with the same exit code.
    message, code = command_line_output_error(inkgraph_executable, model, shade_map, tmp_path, "--shading", "comic",
                                              "--shademap", str(shade_map))
    assert (message, code) == (f"-o '{shade_map}' is the --shademap itself; choose another file", 2)
    # Another name is written as ever.
    result.write(tmp_path / "picture.png")
    assert np.array_equal(read_png(tmp_path / "picture.png"), result.picture)
