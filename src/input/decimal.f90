!> Decimal numbers in text: their syntax and their value.
!>
!> decimal_value gives the value a list-directed read gives (the same bits) at a fraction of
!> its cost: an internal read allocates and locks per statement, which a CSV file of millions
!> of numbers spent most of its time in.
module ddc_input_decimal
    use, intrinsic :: iso_fortran_env, only: int64
    use ddc_kinds, only: wp
    implicit none
    private

    public :: is_number, decimal_value

    !> Most significant digits of an exact integer in double precision (10^15 < 2^53)
    integer, parameter :: exact_digits = 15
    !> The powers of ten that double precision holds exactly
    real(wp), parameter :: exact_powers(0:22) = [1.0e0_wp, 1.0e1_wp, 1.0e2_wp, 1.0e3_wp, &
        1.0e4_wp, 1.0e5_wp, 1.0e6_wp, 1.0e7_wp, 1.0e8_wp, 1.0e9_wp, 1.0e10_wp, 1.0e11_wp, &
        1.0e12_wp, 1.0e13_wp, 1.0e14_wp, 1.0e15_wp, 1.0e16_wp, 1.0e17_wp, 1.0e18_wp, &
        1.0e19_wp, 1.0e20_wp, 1.0e21_wp, 1.0e22_wp]

contains

    !> True when s is a decimal number: [sign] digits [. digits] [e|d [sign] digits].
    pure function is_number(s) result(ok)
        character(len=*), intent(in) :: s
        logical :: ok
        integer :: i, n, ndigits

        ok = .false.
        n = len(s)
        i = 1
        if (n == 0) return
        if (s(1:1) == '+' .or. s(1:1) == '-') i = 2
        ndigits = 0
        do while (i <= n)
            if (.not. is_digit(s(i:i))) exit
            ndigits = ndigits + 1
            i = i + 1
        end do
        if (i <= n) then
            if (s(i:i) == '.') then
                i = i + 1
                do while (i <= n)
                    if (.not. is_digit(s(i:i))) exit
                    ndigits = ndigits + 1
                    i = i + 1
                end do
            end if
        end if
        if (ndigits == 0) return
        if (i <= n) then
            if (index('eEdD', s(i:i)) == 0) return
            i = i + 1
            if (i <= n) then
                if (s(i:i) == '+' .or. s(i:i) == '-') i = i + 1
            end if
            if (i > n) return
            do while (i <= n)
                if (.not. is_digit(s(i:i))) return
                i = i + 1
            end do
        end if
        ok = .true.
    end function is_number

    !> The value of s, a number as is_number accepts it, as a list-directed read gives it;
    !> stat is that read's status (non-zero, and value 0, for a value beyond double precision).
    !> With at most 15 significant digits and a power of ten within 22, the value is one
    !> correctly rounded product or quotient of two exact doubles (Clinger's fast path), as
    !> the read's correctly rounded conversion; any other number is read.
    subroutine decimal_value(s, value, stat)
        character(len=*), intent(in) :: s
        real(wp), intent(out) :: value
        integer, intent(out) :: stat
        integer(int64) :: digits
        integer :: i, n, significant, scale, power, exponent
        logical :: point, negative_exponent

        n = len(s)
        i = 1
        if (s(1:1) == '+' .or. s(1:1) == '-') i = 2
        digits = 0
        significant = 0
        scale = 0
        point = .false.
        do while (i <= n)
            if (s(i:i) == '.') then
                point = .true.
            else if (is_digit(s(i:i))) then
                if (digits > 0 .or. s(i:i) /= '0') then
                    significant = significant + 1
                    if (significant > exact_digits) exit
                    digits = 10 * digits + (iachar(s(i:i)) - iachar('0'))
                end if
                if (point) scale = scale - 1
            else
                exit
            end if
            i = i + 1
        end do
        exponent = 0
        negative_exponent = .false.
        if (i <= n .and. significant <= exact_digits) then
            ! the exponent: e|d [sign] digits, at most 4 of them (it is read beyond)
            i = i + 1
            if (s(i:i) == '+' .or. s(i:i) == '-') then
                negative_exponent = s(i:i) == '-'
                i = i + 1
            end if
            if (n - i + 1 <= 4) then
                do while (i <= n)
                    exponent = 10 * exponent + (iachar(s(i:i)) - iachar('0'))
                    i = i + 1
                end do
            end if
        end if
        if (negative_exponent) exponent = -exponent
        power = scale + exponent
        if (i <= n .or. abs(power) > ubound(exact_powers, 1)) then
            read (s, *, iostat=stat) value
            if (stat /= 0) value = 0.0_wp
            return
        end if
        stat = 0
        if (power >= 0) then
            value = real(digits, wp) * exact_powers(power)
        else
            value = real(digits, wp) / exact_powers(-power)
        end if
        if (s(1:1) == '-') value = -value
    end subroutine decimal_value

    pure function is_digit(c) result(yes)
        character(len=1), intent(in) :: c
        logical :: yes

        yes = c >= '0' .and. c <= '9'
    end function is_digit

end module ddc_input_decimal
