"""What the installed package ships: its types and its licences."""

from importlib import metadata, resources

import microslip


def test_the_types_ship():
    package = resources.files("microslip")
    assert package.joinpath("py.typed").is_file()
    assert package.joinpath("_microslip.pyi").is_file()


def test_the_licences_ship_with_the_metadata():
    assert microslip.__version__ == metadata.version("microslip")
    assert metadata.metadata("microslip")["License-Expression"] == (
        "(MIT OR Apache-2.0) AND LGPL-3.0-or-later"
    )
    shipped = {path.name for path in metadata.files("microslip") or [] if "LICENSES" in str(path)}
    assert shipped == {"LICENSE-MIT", "LICENSE-APACHE", "LGPL-3.0.txt", "GPL-3.0.txt", "NOTICE"}
    lgpl = next(p for p in metadata.files("microslip") or [] if p.name == "LGPL-3.0.txt")
    assert "GNU LESSER GENERAL PUBLIC LICENSE" in lgpl.read_text()
    assert "Version 3" in lgpl.read_text()
