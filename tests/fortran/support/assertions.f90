!> What the Fortran suites assert beyond pFUnit's own assertions.
!>
!> `@assert_that(label, actual, close_to(expected, rel_tol=r, abs_tol=a))` passes when `actual`
!> is finite and |actual - expected| <= max(a, r |expected|), the one rule every tolerance of
!> the suites is written for; at least one of the tolerances must be given. A failure names
!> the file and line (pFUnit), the label, the expected value, the tolerance and what was
!> found. `message_of(error)` is the failure text of a routine under test that returned an
!> error it should not have.
module ddc_test_assertions
    use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
    use ddc_kinds, only: wp
    use ddc_error, only: error_type
    use funit, only: AbstractMatcher, MatcherDescription
    implicit none
    private

    public :: close_to, message_of

    !> A real within a tolerance of an expected value (pFUnit's fHamcrest matcher interface).
    type, extends(AbstractMatcher) :: close_to_matcher
        !> The expected value
        real(wp) :: expected = 0.0_wp
        !> max(abs_tol, rel_tol |expected|)
        real(wp) :: tolerance = 0.0_wp
        !> How the tolerance was given, for the description
        character(len=:), allocatable :: tolerance_given
    contains
        procedure :: matches
        procedure :: describe_to
        procedure :: describe_mismatch
    end type close_to_matcher

contains

    !> The matcher of a finite real within max(abs_tol, rel_tol |expected|) of expected.
    function close_to(expected, rel_tol, abs_tol) result(matcher)
        !> The value expected
        real(wp), intent(in) :: expected
        !> Relative and absolute tolerance (at least one must be given)
        real(wp), intent(in), optional :: rel_tol, abs_tol
        type(close_to_matcher) :: matcher

        matcher%expected = expected
        matcher%tolerance_given = ''
        if (present(abs_tol)) then
            matcher%tolerance = abs_tol
            matcher%tolerance_given = 'abs_tol '//real_text(abs_tol)
        end if
        if (present(rel_tol)) then
            matcher%tolerance = max(matcher%tolerance, rel_tol * abs(expected))
            if (present(abs_tol)) matcher%tolerance_given = matcher%tolerance_given//', '
            matcher%tolerance_given = matcher%tolerance_given//'rel_tol '//real_text(rel_tol)
        end if
    end function close_to

    !> True when actual is a finite real(wp) within the tolerance of the expected value.
    logical function matches(this, actual_value)
        class(close_to_matcher), intent(in) :: this
        class(*), intent(in) :: actual_value

        matches = .false.
        if (this%tolerance_given == '') return
        select type (actual_value)
        type is (real(wp))
            matches = ieee_is_finite(actual_value) &
                      .and. abs(actual_value - this%expected) <= this%tolerance
        end select
    end function matches

    !> "a finite value within T of E (abs_tol a, rel_tol r)".
    subroutine describe_to(this, description)
        class(close_to_matcher), intent(in) :: this
        class(MatcherDescription), intent(inout) :: description

        if (this%tolerance_given == '') then
            call description%append_text('a tolerance: close_to needs rel_tol or abs_tol')
            return
        end if
        call description%append_text('a finite value within '//real_text(this%tolerance)// &
                                     ' of '//real_text(this%expected)//' ('// &
                                     this%tolerance_given//')')
    end subroutine describe_to

    !> "was A, difference D, relative error R".
    subroutine describe_mismatch(this, actual, description)
        class(close_to_matcher), intent(in) :: this
        class(*), intent(in) :: actual
        class(MatcherDescription), intent(inout) :: description

        select type (actual)
        type is (real(wp))
            call description%append_text('was '//real_text(actual)//', difference '// &
                                         real_text(actual - this%expected))
            if (this%expected /= 0.0_wp) then
                call description%append_text(', relative error '// &
                    real_text(abs(actual - this%expected) / abs(this%expected)))
            end if
        class default
            call description%append_text('was not a real(wp)')
        end select
    end subroutine describe_mismatch

    !> The failure text of an unexpected error: its code and message ('' when none).
    function message_of(error) result(text)
        !> The error returned by the routine under test
        type(error_type), allocatable, intent(in) :: error
        character(len=:), allocatable :: text
        character(len=12) :: code

        text = ''
        if (.not. allocated(error)) return
        write (code, '(i0)') error%code
        text = 'unexpected error (code '//trim(code)//'): '//error%message
    end function message_of

    !> A real with all its digits.
    function real_text(value) result(text)
        real(wp), intent(in) :: value
        character(len=:), allocatable :: text
        character(len=32) :: buffer

        write (buffer, '(es24.16)') value
        text = trim(adjustl(buffer))
    end function real_text

end module ddc_test_assertions
