"""The section of a filter key (doc/configuration.md "Key reference"; libs/common model_keys.cpp):
the capability modules own their keys in [ObjectModel] (cv_*, ca_*, mm_*), [OdometryBias]
(odometry_dt, bias_*) and [Classify] (classify_*); every other key of the filter is in
[DynamicKFSLAM]. Used by the scripts that write INI files with extra keys."""
import re

CORE = "DynamicKFSLAM"
MODULES = ("ObjectModel", "OdometryBias", "Classify")


def section_of(key):
    k = key.strip().lower()
    if k.startswith("classify_"):
        return "Classify"
    if re.match(r"(cv|ca|mm)_", k):
        return "ObjectModel"
    if k.startswith("bias_") or k == "odometry_dt":
        return "OdometryBias"
    return CORE


def split_keys(keys):
    """(the [DynamicKFSLAM] keys, the module keys as INI text of their own sections)."""
    core = {k: v for k, v in keys.items() if section_of(k) == CORE}
    text = ""
    for m in MODULES:
        mine = [(k, v) for k, v in keys.items() if section_of(k) == m]
        if mine:
            text += "\n[%s]\n" % m + "".join("%s = %s\n" % kv for kv in mine)
    return core, text
