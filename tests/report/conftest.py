import pytest

from tests.report.report_run import checked


@pytest.fixture(scope="session")
def small_check(tmp_path_factory):
    """(folder, exit code) of one check of the baseline's selection (report_run.SELECTION), one process."""
    return checked(str(tmp_path_factory.mktemp("check1")), 1)


@pytest.fixture(scope="session")
def small_check_two_jobs(tmp_path_factory):
    return checked(str(tmp_path_factory.mktemp("check2")), 2)
