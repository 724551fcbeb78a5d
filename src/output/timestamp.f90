!> The current date and time in UTC for self-describing output (ISO 8601).
module ddc_output_timestamp
    use ddc_kinds, only: wp
    implicit none
    private

    public :: utc_timestamp

contains

    !> The current date and time in UTC, ISO 8601 (YYYY-MM-DDThh:mm:ssZ).
    function utc_timestamp() result(stamp)
        character(len=20) :: stamp
        integer :: values(8), days, minutes, year, month, day

        call date_and_time(values=values)
        ! values: year, month, day, offset from UTC [min], hour, minute, second, ms
        if (values(4) == -huge(0)) values(4) = 0  ! offset unknown: take local as UTC
        days = days_from_civil(values(1), values(2), values(3))
        minutes = values(5) * 60 + values(6) - values(4)
        days = days + floor(real(minutes, wp) / 1440.0_wp)
        minutes = modulo(minutes, 1440)
        call civil_from_days(days, year, month, day)
        write (stamp, '(i4.4,"-",i2.2,"-",i2.2,"T",i2.2,":",i2.2,":",i2.2,"Z")') &
            year, month, day, minutes / 60, modulo(minutes, 60), values(7)
    end function utc_timestamp

    !> Days since 1970-01-01 of a proleptic Gregorian date (H. Hinnant's algorithm).
    pure function days_from_civil(year, month, day) result(days)
        integer, intent(in) :: year, month, day
        integer :: days, y, era, yoe, doy, doe

        y = year
        if (month <= 2) y = y - 1
        era = floor(real(y, wp) / 400.0_wp)
        yoe = y - era * 400
        doy = (153 * (month + 9 - 12 * ((month + 9) / 12)) + 2) / 5 + day - 1
        doe = yoe * 365 + yoe / 4 - yoe / 100 + doy
        days = era * 146097 + doe - 719468
    end function days_from_civil

    !> Proleptic Gregorian date of a day count since 1970-01-01 (H. Hinnant's algorithm).
    pure subroutine civil_from_days(days, year, month, day)
        integer, intent(in) :: days
        integer, intent(out) :: year, month, day
        integer :: z, era, doe, yoe, doy, mp

        z = days + 719468
        era = floor(real(z, wp) / 146097.0_wp)
        doe = z - era * 146097
        yoe = (doe - doe / 1460 + doe / 36524 - doe / 146096) / 365
        doy = doe - (365 * yoe + yoe / 4 - yoe / 100)
        mp = (5 * doy + 2) / 153
        day = doy - (153 * mp + 2) / 5 + 1
        if (mp < 10) then
            month = mp + 3
        else
            month = mp - 9
        end if
        year = yoe + era * 400
        if (month <= 2) year = year + 1
    end subroutine civil_from_days

end module ddc_output_timestamp
