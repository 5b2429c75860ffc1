"""The reference names a study report reads from its file's ``published`` entries."""
from gfbopt.studies.report import _reference_names


def test_published_tables_paths_and_absence():
    """A table names its references; a file of published values (a path, as the transient
    maps give) and a study without any give none — neither the characters of the path nor a
    crash on None (which once lost a finished transient map when its README was written)."""
    assert sorted(_reference_names({"yang": {}, "thesis": {}})) == ["thesis", "yang"]
    assert _reference_names("published/mohan_2010_stability.toml") == []
    assert _reference_names(None) == []
