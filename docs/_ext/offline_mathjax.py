"""Typesets the site's maths with a MathJax the site carries, so that pages read offline.

Debian's libjs-mathjax (MathJax 2) and fonts-mathjax packages, when installed, are the source:
the parts a TeX page needs in the CommonHTML output (the loader, one combined configuration,
the TeX input, the output, its extensions and web fonts, about 1.6 MB) are copied into
_static/mathjax. Without them the pages load MathJax 3 from its CDN, as Sphinx does by
default, and the build says so."""

from __future__ import annotations

import shutil
from pathlib import Path
from typing import Any

from sphinx.application import Sphinx
from sphinx.config import Config
from sphinx.util import logging

logger = logging.getLogger(__name__)

DEBIAN_MATHJAX = Path("/usr/share/javascript/mathjax")
CONFIGURATION = "TeX-AMS_CHTML"
# what MathJax 2 loads for TeX in CommonHTML, relative to its root
PARTS = ["MathJax.js", f"config/{CONFIGURATION}.js", "jax/input/TeX", "jax/output/CommonHTML",
         "jax/element", "extensions", "fonts/HTML-CSS/TeX/woff", "localization/en"]


def _local_mathjax() -> Path | None:
    needed = [DEBIAN_MATHJAX / part for part in PARTS]
    return DEBIAN_MATHJAX if all(path.exists() for path in needed) else None


def _choose(app: Sphinx, config: Config) -> None:
    if _local_mathjax() is None:
        logger.info("MathJax: libjs-mathjax and fonts-mathjax are not installed; the pages "
                    "load MathJax from its CDN (their maths needs the network)")
        return
    config.mathjax_path = f"mathjax/MathJax.js?config={CONFIGURATION}"
    # MyST-NB marks its pages' text tex2jax_ignore and asks MathJax 3 to process the maths
    # inside it; MathJax 2 takes the same classes from its tex2jax settings
    config.mathjax2_config = {"tex2jax": {
        "processClass": "tex2jax_process|mathjax_process|math|output_area"}}


def _copy(app: Sphinx, exception: Exception | None) -> None:
    source = _local_mathjax()
    if exception is not None or source is None or app.builder.format != "html":
        return
    target = Path(app.outdir) / "_static" / "mathjax"
    for part in PARTS:
        origin = source / part
        if origin.is_dir():
            shutil.copytree(origin, target / part, dirs_exist_ok=True)
        else:
            (target / part).parent.mkdir(parents=True, exist_ok=True)
            shutil.copy2(origin, target / part)


def setup(app: Sphinx) -> dict[str, Any]:
    app.connect("config-inited", _choose)
    app.connect("build-finished", _copy)
    return {"parallel_read_safe": True, "parallel_write_safe": True}
