"""The architecture checks fail when fed a planted violation (CTest architecture_checks).

Each case copies the sources the checks read (src/, app/, tests/fortran/, tests/mpi/,
tests/python/, scripts/ and docs/ARCHITECTURE.md) to a temporary folder, plants one
violation, and expects check_sources.py to exit 1 naming it; the copy as it is must pass, so
each failure comes from the planted line alone.
"""

import re
import shutil
import sys
from pathlib import Path

import pytest

sys.dont_write_bytecode = True
HERE = Path(__file__).resolve().parent
REPO_ROOT = HERE.parents[1]
sys.path.insert(0, str(HERE))

import check_sources  # noqa: E402  (imported from this folder)


@pytest.fixture
def tree(tmp_path):
    """A copy of the sources the checks read."""
    for folder in ("src", "app"):
        shutil.copytree(REPO_ROOT / folder, tmp_path / folder)
    shutil.copytree(REPO_ROOT / "tests/fortran", tmp_path / "tests/fortran")
    (tmp_path / "docs").mkdir()
    shutil.copy(REPO_ROOT / "docs/ARCHITECTURE.md", tmp_path / "docs")
    # named by the recipes; python/ holds the reader of result files (check 11)
    for folder in ("tests/mpi", "tests/python", "scripts", "python"):
        shutil.copytree(REPO_ROOT / folder, tmp_path / folder,
                        ignore=shutil.ignore_patterns("__pycache__"))
    return tmp_path


def run_checks(root, capsys):
    status = check_sources.main([str(root)])
    return status, capsys.readouterr().out


def expect_violation(root, capsys, message):
    """The checks fail on root and name the violation."""
    status, out = run_checks(root, capsys)
    assert status == 1, out
    assert message in out, out


def edit(path, old, new):
    """Replace the one occurrence of old in path by new."""
    text = path.read_text()
    assert text.count(old) == 1, f"{path}: {old!r} occurs {text.count(old)} times"
    path.write_text(text.replace(old, new))


def table_row(tree, folder):
    text = (tree / "docs/ARCHITECTURE.md").read_text()
    return re.search(rf"^\| `{re.escape(folder)}` .*$", text, re.MULTILINE).group(0)


def test_the_tree_passes(tree, capsys):
    status, out = run_checks(tree, capsys)
    assert status == 0, out
    assert "every folder edge listed" in out


def test_unlisted_folder_edge_fails(tree, capsys):
    # sweep/ back on the HDF5 reader, the edge this table no longer lists
    edit(tree / "src/sweep/tasks.f90", "    use ddc_kinds, only: wp\n",
         "    use ddc_kinds, only: wp\n    use ddc_output_hdf5_read, only: read_int_attribute\n")
    expect_violation(tree, capsys,
                     "src/sweep/tasks.f90 uses ddc_output_hdf5_read: the folder table of "
                     "docs/ARCHITECTURE.md does not list output (nor output/hdf5_read one by "
                     "one) among the uses of sweep")


def test_unlisted_module_of_listed_folder_fails(tree, capsys):
    # model/ lists contact/options and contact/states only, not all of contact/
    edit(tree / "src/model/results.f90", "    use ddc_kinds, only: wp\n",
         "    use ddc_kinds, only: wp\n    use ddc_contact_lemke, only: solve_lemke\n")
    expect_violation(tree, capsys,
                     "src/model/results.f90 uses ddc_contact_lemke: the folder table of "
                     "docs/ARCHITECTURE.md does not list contact (nor contact/lemke one by "
                     "one) among the uses of model")


def test_listed_use_the_code_lacks_fails(tree, capsys):
    row = table_row(tree, "linalg/")
    edit(tree / "docs/ARCHITECTURE.md", row, row.replace("| base |", "| base, mesh |"))
    expect_violation(tree, capsys, "docs/ARCHITECTURE.md: the row of linalg lists mesh, which "
                     "linalg does not use")


def test_folder_without_row_fails(tree, capsys):
    row = table_row(tree, "post/")
    edit(tree / "docs/ARCHITECTURE.md", row + "\n", "")
    expect_violation(tree, capsys, "docs/ARCHITECTURE.md: no row for post in the folder table")


def test_per_element_array_missing_from_the_list_fails(tree, capsys):
    edit(tree / "src/model/types.f90", "        integer :: domain = domain_full_plane\n",
         "        integer :: domain = domain_full_plane\n"
         "        real(wp), allocatable :: planted(:)\n")
    expect_violation(tree, capsys, "src/model/types.f90: the per-element array planted of "
                     "element_set is missing from for_each_element_array")
    # listed once, it passes
    edit(tree / "src/model/types.f90", "        call action%on_reals(elements%sin_beta)\n",
         "        call action%on_reals(elements%sin_beta)\n"
         "        call action%on_reals(elements%planted)\n")
    assert run_checks(tree, capsys)[0] == 0


def test_routine_around_the_list_fails(tree, capsys):
    edit(tree / "src/parallel/model.f90",
         "        call for_each_element_array(elements, broadcast)\n", "")
    expect_violation(tree, capsys, "src/parallel/model.f90: share_elements does not go "
                     "through for_each_element_array")


def test_element_scalar_missing_from_the_broadcast_fails(tree, capsys):
    edit(tree / "src/parallel/model.f90",
         "        call share(context, elements%symmetry%ysym)\n", "")
    expect_violation(tree, capsys, "src/parallel/model.f90: share_elements does not broadcast "
                     "elements%symmetry%ysym (a component of element_set)")


def test_solver_option_missing_from_the_broadcast_fails(tree, capsys):
    edit(tree / "src/contact/options.f90", "        integer :: open_cohesion = cohesion_kept\n",
         "        integer :: open_cohesion = cohesion_kept\n        integer :: planted = 0\n")
    expect_violation(tree, capsys, "src/parallel/model.f90: share_model does not broadcast "
                     "model%solver%planted (a component of solver_options) nor marks it")
    # marked root only, with a reason, and hashed in the fingerprint, it passes
    edit(tree / "src/parallel/model.f90", "        ! Root only: model%solver%work_bytes",
         "        ! Root only: model%solver%planted (planted)\n"
         "        ! Root only: model%solver%work_bytes")
    edit(tree / "src/model/fingerprint.f90", "model%solver%open_cohesion, &",
         "model%solver%open_cohesion, model%solver%planted, &")
    assert run_checks(tree, capsys)[0] == 0


def test_stale_root_only_mark_fails(tree, capsys):
    edit(tree / "src/parallel/model.f90", "        ! Root only: model%solver%work_bytes",
         "        ! Root only: model%solver%gone (planted)\n"
         "        ! Root only: model%solver%work_bytes")
    expect_violation(tree, capsys, "src/parallel/model.f90: share_model marks "
                     "model%solver%gone root only, which is no component of solver_options")


def test_folder_cycle_fails(tree, capsys):
    # linalg/ -> model/ closes model -> contact -> linalg
    edit(tree / "src/linalg/lu.f90", "    use ddc_kinds, only: wp\n",
         "    use ddc_kinds, only: wp\n    use ddc_model_types, only: model_type\n")
    expect_violation(tree, capsys, "linalg -> model (src/linalg/lu.f90 uses ddc_model_types)")


def test_module_name_off_its_path_fails(tree, capsys):
    edit(tree / "src/post/tips.f90", "\nmodule ddc_post_tips\n", "\nmodule ddc_post_tip\n")
    expect_violation(tree, capsys, "src/post/tips.f90: holds module ddc_post_tip, expected "
                     "ddc_post_tips")


def test_namelist_off_the_group_table_fails(tree, capsys):
    edit(tree / "src/input/namelist_fracture.f90", "namelist /fracture/ name, x, y,",
         "namelist /fracture/ name, y, x,")
    expect_violation(tree, capsys,
                     "src/input/namelist_fracture.f90: namelist /fracture/ declares")


def test_unused_import_fails(tree, capsys):
    edit(tree / "src/linalg/lu.f90", "    use ddc_kinds, only: wp\n",
         "    use ddc_kinds, only: wp\n    use ddc_sorting, only: first_at_least\n")
    expect_violation(tree, capsys,
                     "src/linalg/lu.f90: imports first_at_least but does not use it")


def test_error_of_a_routine_under_test_not_read_fails(tree, capsys):
    # test_lemke: a solve whose error is asserted on; without the assertion, the next solve
    # would overwrite it unseen
    path = tree / "tests/fortran/test_lemke.pf"
    text = path.read_text()
    seen = re.search(r"\n( +call solve_lcp_lemke\([^\n]*error[^\n]*)\n +@assertFalse\(allocated"
                     r"\(error\), message_of\(error\)\)\n", text)
    assert seen, "test_lemke.pf changed: pick another planted line"
    path.write_text(text[:seen.start()] + "\n" + seen.group(1) + "\n" + text[seen.end():])
    expect_violation(tree, capsys, "the error this call returns is")


def test_model_component_missing_from_the_fingerprint_fails(tree, capsys):
    edit(tree / "src/model/types.f90", "        real(wp) :: new_mu = 0.0_wp, new_sf = 0.0_wp\n",
         "        real(wp) :: new_mu = 0.0_wp, new_sf = 0.0_wp\n        integer :: planted = 0\n")
    expect_violation(tree, capsys, "src/model/fingerprint.f90: hash_model does not hash "
                     "model%growth%planted nor marks it '! Not hashed: model%growth%planted")
    # marked not hashed, with a reason, it passes
    edit(tree / "src/model/fingerprint.f90", "        ! Not hashed: model%fingerprint (this hash)",
         "        ! Not hashed: model%fingerprint (this hash)\n"
         "        ! Not hashed: model%growth%planted (planted)")
    assert run_checks(tree, capsys)[0] == 0


def test_fingerprint_around_the_element_list_fails(tree, capsys):
    edit(tree / "src/model/fingerprint.f90",
         "        call for_each_element_array(elements, hash)\n", "")
    expect_violation(tree, capsys, "src/model/fingerprint.f90: hash_model does not go through "
                     "for_each_element_array")


def test_stale_not_hashed_mark_fails(tree, capsys):
    edit(tree / "src/model/fingerprint.f90", "        ! Not hashed: model%fingerprint (this hash)",
         "        ! Not hashed: model%fingerprint (this hash)\n"
         "        ! Not hashed: model%gone (planted)")
    expect_violation(tree, capsys, "src/model/fingerprint.f90: hash_model marks model%gone not "
                     "hashed, which is no component of the model")


@pytest.mark.parametrize("planted_in, message", [
    ("src/contact/lemke.f90",
     ("src/contact/lemke.f90: the LCP solver ddc_contact_lemke reaches the fault law "
      "(ddc_contact_lemke -> ddc_contact_fault_law)")),
    # the stiffness operator, which the active-set method uses
    ("src/contact/stiffness.f90",
     ("src/contact/active_set.f90: the LCP solver ddc_contact_active_set reaches the fault "
      "law (ddc_contact_active_set -> ddc_contact_stiffness -> ddc_contact_fault_law)"))])
def test_lcp_solver_reaching_the_fault_law_fails(tree, capsys, planted_in, message):
    edit(tree / planted_in, "    use ddc_kinds, only: wp\n",
         "    use ddc_kinds, only: wp\n    use ddc_contact_fault_law, only: fault_law\n")
    expect_violation(tree, capsys, message)


def test_growth_criterion_without_its_case_fails(tree, capsys):
    edit(tree / "src/model/types.f90",
         "    integer, parameter :: growth_criterion_mts = 1, growth_criterion_work = 2\n",
         "    integer, parameter :: growth_criterion_mts = 1, growth_criterion_work = 2, "
         "growth_criterion_planted = 3\n")
    expect_violation(tree, capsys, "src/growth/criterion.f90: assess_tip has no case for "
                     "growth_criterion_planted")
    expect_violation(tree, capsys, "src/growth/criterion.f90: kink_angles has no case for "
                     "growth_criterion_planted")
    expect_violation(tree, capsys, "src/growth/criterion.f90: assess_flaw has no case for "
                     "growth_criterion_planted")
    # with its case in every dispatch, it passes
    path = tree / "src/growth/criterion.f90"
    text = path.read_text()
    assert text.count("        case (growth_criterion_mts") == 3
    path.write_text(text.replace("        case (growth_criterion_mts",
                                 "        case (growth_criterion_planted, growth_criterion_mts"))
    assert run_checks(tree, capsys)[0] == 0


def test_growth_criterion_dispatch_without_default_fails(tree, capsys):
    edit(tree / "src/growth/criterion.f90",
         "        case default\n            call unknown_criterion('assess_tip', "
         "options%criterion, error)\n", "")
    expect_violation(tree, capsys, "src/growth/criterion.f90: assess_tip dispatches on the "
                     "criterion without a case default")


def test_growth_criterion_read_outside_the_dispatch_fails(tree, capsys):
    edit(tree / "src/growth/driver.f90", "        now%reason = reason_stopped\n",
         "        now%reason = reason_stopped\n"
         "        if (options%criterion /= growth_criterion_mts) return\n")
    expect_violation(tree, capsys, "src/growth/driver.f90: reads the growth criterion "
                     "(%criterion) outside src/growth/criterion.f90")


def test_history_column_missing_from_its_list_fails(tree, capsys):
    edit(tree / "src/model/results.f90", "        real(wp), allocatable :: grown_length(:, :)\n",
         "        real(wp), allocatable :: grown_length(:, :)\n"
         "        real(wp), allocatable :: planted(:)\n")
    expect_violation(tree, capsys, "src/model/results.f90: the column planted of "
                     "history_record is missing from for_each_history_column")
    # listed, the Python reader does not know its dataset yet
    edit(tree / "src/model/records.f90",
         "                             history%equilibrium_residual)\n",
         "                             history%equilibrium_residual)\n"
         "        call action%on_reals(column('planted', column_steps, units_one), "
         "history%planted)\n")
    expect_violation(tree, capsys, "python/src/ddc2d/reader.py: HISTORY_DATASETS + "
                     "HISTORY_STEP_DATASETS lacks 'planted', one of the other datasets of "
                     "/history")
    # read by the Python reader too, it passes
    edit(tree / "python/src/ddc2d/reader.py", '"equilibrium_residual")',
         '"equilibrium_residual", "planted")')
    assert run_checks(tree, capsys)[0] == 0


def test_growth_column_missing_from_its_list_fails(tree, capsys):
    edit(tree / "src/model/results.f90", "        integer, allocatable :: reason(:)\n",
         "        integer, allocatable :: reason(:)\n        integer, allocatable :: planted(:)\n")
    expect_violation(tree, capsys, "src/model/results.f90: the column planted of "
                     "tip_records is missing from for_each_tip_column")


def test_column_under_another_name_fails(tree, capsys):
    edit(tree / "src/model/records.f90", "column('k_eq', column_records, units_k), rows%k_eq",
         "column('k_eqq', column_records, units_k), rows%k_eq")
    expect_violation(tree, capsys, "src/model/records.f90: for_each_tip_column names the "
                     "column rows%k_eq 'k_eqq'")


def test_initiation_and_trial_columns_fail_off_their_lists(tree, capsys):
    edit(tree / "src/model/initiations.f90", "        real(wp), allocatable :: tension(:)\n",
         "        real(wp), allocatable :: tension(:), planted(:)\n")
    expect_violation(tree, capsys, "src/model/initiations.f90: the column planted of "
                     "initiation_record is missing from for_each_initiation_column")
    edit(tree / "src/model/trial_records.f90", "        integer, allocatable :: state(:)\n",
         "        integer, allocatable :: state(:), planted(:)\n")
    expect_violation(tree, capsys, "src/model/trial_records.f90: the column planted of "
                     "trial_records is missing from for_each_trial_column")


def test_record_part_not_handed_to_its_list_fails(tree, capsys):
    edit(tree / "src/model/records.f90",
         "        call for_each_trial_column(record%trials, action)\n"
         "        call action%on_integers(column('created_step'",
         "        call action%on_integers(column('created_step'")
    expect_violation(tree, capsys, "src/model/records.f90: for_each_growth_column does not hand "
                     "record%trials to for_each_trial_column")


def test_trial_datasets_off_the_python_lists_fail(tree, capsys):
    edit(tree / "python/src/ddc2d/reader.py", '"step", "flaw", "angle"', '"step", "owner", "angle"')
    expect_violation(tree, capsys, "python/src/ddc2d/reader.py: FLAW_TRIAL_DATASETS lacks 'flaw'")


def test_routine_around_a_record_list_fails(tree, capsys):
    edit(tree / "src/output/hdf5_records.f90",
         "        call for_each_growth_column(columns, writer)\n"
         "        if (writer%work)", "        if (writer%work)")
    expect_violation(tree, capsys, "src/output/hdf5_records.f90: write_growth does not go "
                     "through for_each_growth_column")


def test_python_dataset_lists_off_the_record_lists_fail(tree, capsys):
    edit(tree / "python/src/ddc2d/reader.py", '"tip_fracture_id", "tip_end")', '"tip_fracture_id")')
    edit(tree / "python/src/ddc2d/reader.py", '"corrections", "k2_after", "length", "reason")',
         '"corrections", "k2_after", "length", "reason", "planted")')
    expect_violation(tree, capsys, "python/src/ddc2d/reader.py: HISTORY_GROWTH_DATASETS lacks "
                     "'tip_end', one of the columns of for_each_history_column it holds")
    expect_violation(tree, capsys, "python/src/ddc2d/reader.py: GROWTH_DATASETS names 'planted', "
                     "which is not one of the columns of for_each_tip_column it holds")


def test_python_loads_off_load_path_names_fail(tree, capsys):
    edit(tree / "python/src/ddc2d/reader.py", '"dsxy_dy", "p0")', '"p0", "dsxy_dy")')
    expect_violation(tree, capsys, "python/src/ddc2d/reader.py: HISTORY_LOADS ")


def test_strength_law_off_what_holds_it_fails(tree, capsys):
    # A law listed, and nowhere else yet
    edit(tree / "src/model/laws.f90",
         "units_stiffness, beyond_coulomb=.true.), elements%normal_stiffness)\n",
         "units_stiffness, beyond_coulomb=.true.), elements%normal_stiffness)\n"
         "        call action%on_law(law('planted', 0.0_wp, quantity_non_negative, "
         "units_length, &\n                               beyond_coulomb=.false.), "
         "elements%planted)\n")
    for message in [
            "src/model/laws.f90: the law planted of for_each_law is no per-element real array",
            "src/model/types.f90: strength_law_count = 7, but for_each_law",
            "src/contact/fault_law.f90: fault_law has no component planted",
            "src/contact/fault_law.f90: set_given lacks 'planted'",
            "src/contact/fault_law.f90: new_fault_law's given_or lacks 'planted'",
            "src/input/namelist_fracture.f90: namelist /fracture/ does not declare planted",
            "src/input/namelist_growth.f90: namelist /growth/ does not declare new_planted",
            "src/input/namelist_fracture.f90: read_fracture_groups gathers the laws' values",
            "src/input/namelist_growth.f90: read_growth_group gathers the laws' values"]:
        expect_violation(tree, capsys, message)
    # an array of the elements, counted, in the fault law and both namelists: it passes
    types = tree / "src/model/types.f90"
    edit(types, "        integer :: domain = domain_full_plane\n",
         "        integer :: domain = domain_full_plane\n"
         "        real(wp), allocatable :: planted(:)\n")
    edit(types, "        call action%on_reals(elements%sin_beta)\n",
         "        call action%on_reals(elements%sin_beta)\n"
         "        call action%on_reals(elements%planted)\n")
    edit(types, "strength_law_count = 7", "strength_law_count = 8")
    law = tree / "src/contact/fault_law.f90"
    edit(law, "        real(wp), allocatable :: shear_stiffness(:), normal_stiffness(:)\n",
         "        real(wp), allocatable :: shear_stiffness(:), normal_stiffness(:), planted(:)\n")
    edit(law, "        case default\n            ! not a law of this type\n",
         "        case ('planted')\n            law%planted = values\n"
         "        case default\n            ! not a law of this type\n")
    edit(law, "        allocate (law%sf_in_force, source=sf)\n",
         "        allocate (law%planted, source=given_or(planted, 0.0_wp))\n"
         "        allocate (law%sf_in_force, source=sf)\n")
    edit(tree / "src/input/namelist_fracture.f90",
         "            transmissivity, a, b, dc, f0, v0, v_init, sigma0, tau0, residual_aperture\n",
         "            transmissivity, a, b, dc, f0, v0, v_init, sigma0, tau0, residual_aperture, "
         "planted\n")
    edit(tree / "src/input/namelist_fracture.f90", "shear_stiffness, normal_stiffness], &",
         "shear_stiffness, normal_stiffness, planted], &")
    edit(tree / "src/input/namelist_growth.f90",
         "new_shear_stiffness, &\n            new_normal_stiffness\n\n",
         "new_shear_stiffness, &\n            new_normal_stiffness, new_planted\n\n")
    edit(tree / "src/input/namelist_growth.f90", "new_shear_stiffness, new_normal_stiffness], ",
         "new_shear_stiffness, new_normal_stiffness, new_planted], ")
    groups = tree / "src/input/namelist_groups.f90"
    edit(groups, "'residual_aperture:r'", "'residual_aperture:r planted:r'")
    edit(groups, "'new_shear_stiffness:r new_normal_stiffness:r'",
         "'new_shear_stiffness:r new_normal_stiffness:r new_planted:r'")
    status, out = run_checks(tree, capsys)
    assert status == 0, out


def test_strength_law_default_off_the_fault_law_fails(tree, capsys):
    edit(tree / "src/contact/fault_law.f90", "given_or(sf_residual, no_residual_drop)",
         "given_or(sf_residual, 0.0_wp)")
    expect_violation(tree, capsys, "src/contact/fault_law.f90: new_fault_law gives sf_residual "
                     "the default 0.0_wp, for_each_law (src/model/laws.f90) no_residual_drop")


def test_strength_law_beyond_coulomb_off_the_fault_law_fails(tree, capsys):
    laws = tree / "src/model/laws.f90"
    edit(laws, "units_length, beyond_coulomb=.false.), &\n"
         "                           elements%slip_weakening_distance)",
         "units_length, beyond_coulomb=.true.), &\n"
         "                           elements%slip_weakening_distance)")
    edit(laws, "units_stress, beyond_coulomb=.true.), elements%tensile_strength)",
         "units_stress, beyond_coulomb=.false.), elements%tensile_strength)")
    expect_violation(tree, capsys, "src/model/laws.f90: for_each_law marks "
                     "slip_weakening_distance beyond Coulomb, which beyond_coulomb "
                     "(src/contact/fault_law.f90) does not read")
    expect_violation(tree, capsys, "src/model/laws.f90: for_each_law does not mark "
                     "tensile_strength beyond Coulomb, which beyond_coulomb "
                     "(src/contact/fault_law.f90) reads")


def test_strength_laws_gathered_out_of_order_fail(tree, capsys):
    edit(tree / "src/input/namelist_fracture.f90", "shear_stiffness, normal_stiffness], &",
         "normal_stiffness, shear_stiffness], &")
    expect_violation(tree, capsys, "src/input/namelist_fracture.f90: read_fracture_groups "
                     "gathers the laws' values as")


def test_routine_around_the_law_list_fails(tree, capsys):
    # the flaw's new elements would keep element 1's laws
    edit(tree / "src/growth/new_fracture.f90",
         "            call default_strength_laws(grown%elements, [(i > n, i = 1, n + m)])\n",
         "")
    expect_violation(tree, capsys, "src/growth/new_fracture.f90: add_fracture does not go "
                     "through default_strength_laws")


def test_recipe_naming_a_missing_file_fails(tree, capsys):
    edit(tree / "docs/ARCHITECTURE.md", "`src/contact/formulation.f90`: call it from",
         "`src/contact/formulations.f90`: call it from")
    expect_violation(tree, capsys, "docs/ARCHITECTURE.md: a recipe names "
                     "src/contact/formulations.f90, which does not exist")


def test_recipe_naming_a_missing_procedure_fails(tree, capsys):
    for path in (tree / "src/growth/extension.f90", tree / "src/growth/new_fracture.f90"):
        path.write_text(path.read_text().replace("take_new_element_laws", "take_new_laws"))
    expect_violation(tree, capsys, "docs/ARCHITECTURE.md: a recipe names "
                     "take_new_element_laws in src/growth/extension.f90, which has no "
                     "take_new_element_laws")


def test_a_test_naming_tmp_fails(tree, capsys):
    edit(tree / "tests/fortran/test_sweep.pf", "temporary_path('ddc2d_test_sweep_complete.h5')",
         "'/tmp/ddc2d_test_sweep_complete.h5'")
    path = tree / "tests/python/test_cli.py"
    path.write_text(path.read_text() + '\nLEFT = "/tmp/ddc2d_planted"\n')
    expect_violation(tree, capsys, "tests/fortran/test_sweep.pf:")
    expect_violation(tree, capsys, "tests/python/test_cli.py:")
    expect_violation(tree, capsys, "names /tmp: write into the test's own temporary folder")
